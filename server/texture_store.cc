#include "texture_store.h"

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "absl/strings/str_cat.h"
#include "content_hash.h"

namespace aperture {

namespace fs = std::filesystem;

TextureStore::TextureStore(std::string directory) : directory_(std::move(directory)) {}

std::string TextureStore::PathOf(const std::string& sha256) const {
  return (fs::path(directory_) / absl::StrCat(sha256, ".tex")).string();
}

bool TextureStore::Has(const std::string& sha256) const {
  {
    std::lock_guard lock(mutex_);
    if (textures_.count(sha256)) return true;
  }
  std::error_code error;
  return !directory_.empty() && fs::is_regular_file(PathOf(sha256), error);
}

absl::Status TextureStore::Put(const std::string& sha256, std::string bytes) {
  if (const std::string actual = Sha256Hex(bytes); actual != sha256)
    return absl::InvalidArgumentError(
        absl::StrCat("sha256: the content hashes to ", actual, ", not ", sha256));
  if (!directory_.empty()) {
    const std::string temporary = absl::StrCat(PathOf(sha256), ".tmp.", getpid());
    {
      std::ofstream out(temporary, std::ios::binary);
      out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
      if (!out.flush())
        return absl::InternalError(absl::StrCat("cannot write texture file ", temporary));
    }
    std::error_code error;
    fs::rename(temporary, PathOf(sha256), error);
    if (error)
      return absl::InternalError(
          absl::StrCat("cannot publish ", PathOf(sha256), ": ", error.message()));
  }
  std::lock_guard lock(mutex_);
  textures_[sha256] = std::make_shared<const std::string>(std::move(bytes));
  return absl::OkStatus();
}

absl::StatusOr<std::shared_ptr<const std::string>> TextureStore::Get(
    const std::string& sha256) const {
  {
    std::lock_guard lock(mutex_);
    if (auto it = textures_.find(sha256); it != textures_.end()) return it->second;
  }
  if (!directory_.empty()) {
    std::ifstream in(PathOf(sha256), std::ios::binary);
    if (in) {
      std::ostringstream content;
      content << in.rdbuf();
      std::string bytes = std::move(content).str();
      // Files are trusted only after their hash is checked again.
      if (Sha256Hex(bytes) == sha256) {
        auto shared = std::make_shared<const std::string>(std::move(bytes));
        std::lock_guard lock(mutex_);
        textures_[sha256] = shared;
        return shared;
      }
    }
  }
  return absl::NotFoundError(absl::StrCat("texture ", sha256, " is not stored; upload it first"));
}

size_t TextureStore::size() const {
  std::lock_guard lock(mutex_);
  return textures_.size();
}

}  // namespace aperture
