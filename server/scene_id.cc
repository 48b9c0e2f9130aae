#include "scene_id.h"

#include "absl/strings/str_cat.h"
#include "content_hash.h"

namespace aperture {

absl::Status CheckSceneId(const std::string& id) {
  if (IsSha256Hex(id)) return absl::OkStatus();
  constexpr absl::string_view kForm = "the id LoadScene returned, 64 lowercase hex digits";
  if (id.empty())
    return absl::InvalidArgumentError(absl::StrCat("scene_id is empty; give ", kForm));
  if (id.size() != 64)
    return absl::InvalidArgumentError(
        absl::StrCat("scene_id has ", id.size(), " characters; give ", kForm));
  const size_t bad = id.find_first_not_of("0123456789abcdef");
  return absl::InvalidArgumentError(
      absl::StrCat("scene_id: character ", bad + 1, " is not a lowercase hex digit; give ", kForm));
}

}  // namespace aperture
