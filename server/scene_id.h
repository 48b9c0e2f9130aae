// The form of the scene ids LoadScene answers with (SceneRequestId: 64 lowercase hex digits),
// checked before an id is looked up or quoted back: a malformed id is INVALID_ARGUMENT naming
// what is wrong with it, never echoed whole (a 100 KB id in an error would overflow the answer's
// trailers), and only a well-formed unknown id is NOT_FOUND.
#pragma once

#include <string>

#include "absl/status/status.h"

namespace aperture {

absl::Status CheckSceneId(const std::string& id);

}  // namespace aperture
