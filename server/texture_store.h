// Uploaded texture images, content-addressed by SHA-256. Kept in memory and, when a directory is
// given (--store), also as files named by their hash, so a restarted server still has them.
// Files are written to a temporary name and renamed, so a crash never leaves a partial entry.
#pragma once

#include <map>
#include <memory>
#include <mutex>
#include <string>

#include "absl/status/statusor.h"

namespace aperture {

class TextureStore {
 public:
  explicit TextureStore(std::string directory = "");

  bool Has(const std::string& sha256) const;
  // Verifies that `bytes` hash to `sha256`, then keeps them.
  absl::Status Put(const std::string& sha256, std::string bytes);
  absl::StatusOr<std::shared_ptr<const std::string>> Get(const std::string& sha256) const;
  size_t size() const;

 private:
  std::string PathOf(const std::string& sha256) const;

  std::string directory_;
  mutable std::mutex mutex_;
  mutable std::map<std::string, std::shared_ptr<const std::string>> textures_;
};

}  // namespace aperture
