// Uploaded texture images, content-addressed by SHA-256. With a shared store (--store) they live
// there as blob entries ("upload-<sha256>"), mapped read-only and shared by every server process
// on the machine and kept across restarts; without one (--store none) they are kept in memory.
// The shared store also receives the tables and packed textures built from them (engine/store).
#pragma once

#include <map>
#include <memory>
#include <mutex>
#include <set>
#include <string>

#include "absl/status/statusor.h"
#include "store/shared_store.h"

namespace aperture {

class TextureStore {
 public:
  // `shared`: the machine's store, or null for memory only.
  explicit TextureStore(std::shared_ptr<const SharedStore> shared = nullptr);

  bool Has(const std::string& sha256) const;
  // Verifies that `bytes` hash to `sha256` and are a texture (an image header within the limits,
  // or a valid .apv), then keeps them.
  absl::Status Put(const std::string& sha256, std::string bytes);
  absl::StatusOr<std::shared_ptr<const std::string>> Get(const std::string& sha256) const;
  // Uploads this process holds in memory or has mapped from the shared store.
  size_t size() const;
  // Bytes the store takes: the shared directory's entry files (uploads, tables, packed
  // textures), or the uploads held in memory without one.
  uint64_t bytes() const;
  // Evicts least recently used uploads (and, in the shared store, tables) until bytes() is at
  // most `budget_bytes`; returns how many entries went. Scenes built from them keep their pixels.
  uint64_t Trim(uint64_t budget_bytes);
  // Keeps the store within `budget_bytes` as entries come (uploads, and the tables the engine
  // publishes): room is made before an entry is written.
  void SetBudget(uint64_t budget_bytes);
  // Entries evicted to keep within the budget (by this process).
  uint64_t evicted() const;
  const std::shared_ptr<const SharedStore>& shared() const { return shared_; }

 private:
  static std::string KeyOf(const std::string& sha256) { return "upload-" + sha256; }

  std::shared_ptr<const SharedStore> shared_;
  mutable std::mutex mutex_;
  struct MemoryUpload {
    std::shared_ptr<const std::string> bytes;
    uint64_t last_use = 0;
  };
  mutable uint64_t clock_ = 0;
  uint64_t budget_bytes_ = 0;
  uint64_t evicted_ = 0;                                  // memory only
  mutable std::map<std::string, MemoryUpload> textures_;  // memory only
  mutable std::set<std::string> known_;                   // uploads seen in the shared store
};

}  // namespace aperture
