#include "texture_store.h"

#include <span>

#include "absl/strings/str_cat.h"
#include "content_hash.h"
#include "refusal_log.h"
#include "scene/encoded_texture.h"

namespace aperture {

TextureStore::TextureStore(std::shared_ptr<const SharedStore> shared)
    : shared_(std::move(shared)) {}

bool TextureStore::Has(const std::string& sha256) const {
  {
    std::lock_guard lock(mutex_);
    if (textures_.count(sha256)) return true;
  }
  return shared_ && IsSha256Hex(sha256) && shared_->Has(KeyOf(sha256), EntryKind::kBlob);
}

absl::Status TextureStore::Put(const std::string& sha256, std::string bytes) {
  if (const std::string actual = Sha256Hex(bytes); actual != sha256)
    return absl::InvalidArgumentError(
        absl::StrCat("sha256: the content hashes to ", actual, ", not ", sha256));
  // Kept only when it is a texture the engine takes: a raster image whose header OpenImageIO
  // reads within the texture limits, or a valid packed texture.
  if (auto texture = InspectEncodedTexture(
          std::span(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size()));
      !texture.ok())
    return absl::InvalidArgumentError(
        absl::StrCat("upload is not a texture the server can use: ", texture.status().message()));
  if (shared_) {
    // Published whole or not at all (engine/store): a crash mid-upload leaves nothing usable.
    auto entry = shared_->Put(KeyOf(sha256), EntryKind::kBlob, std::as_bytes(std::span(bytes)));
    if (!entry.ok()) {
      absl::Status status(entry.status().code(),
                          absl::StrCat("texture store: ", entry.status().message()));
      return absl::IsResourceExhausted(status) ? MarkRefusal(status, kStoreBudgetRefusal) : status;
    }
  }
  if (shared_) {
    std::lock_guard lock(mutex_);
    known_.insert(sha256);
    return absl::OkStatus();
  }
  const uint64_t size = bytes.size();
  if (budget_bytes_ > 0 && size > budget_bytes_)
    return MarkRefusal(absl::ResourceExhaustedError(absl::StrCat(
                           "an upload of ", size >> 20, " MiB does not fit in the texture store's ",
                           "budget of ", budget_bytes_ >> 20, " MiB (--max-store-mb)")),
                       kStoreBudgetRefusal);
  if (budget_bytes_ > 0) Trim(budget_bytes_ - size);  // room first
  std::lock_guard lock(mutex_);
  textures_[sha256] = {std::make_shared<const std::string>(std::move(bytes)), ++clock_};
  return absl::OkStatus();
}

absl::StatusOr<std::shared_ptr<const std::string>> TextureStore::Get(
    const std::string& sha256) const {
  {
    std::lock_guard lock(mutex_);
    if (auto it = textures_.find(sha256); it != textures_.end()) {
      it->second.last_use = ++clock_;
      return it->second.bytes;
    }
  }
  if (shared_ && IsSha256Hex(sha256)) {
    // The entry's own checksum was verified when it was mapped.
    auto entry = shared_->Attach(KeyOf(sha256), EntryKind::kBlob);
    if (entry.ok()) {
      const auto payload = (*entry)->payload();
      // A copy for the caller only: the mapping stays the one resident copy.
      auto bytes = std::make_shared<const std::string>(
          reinterpret_cast<const char*>(payload.data()), payload.size());
      std::lock_guard lock(mutex_);
      known_.insert(sha256);
      return bytes;
    }
    if (!absl::IsNotFound(entry.status()))
      return absl::DataLossError(
          absl::StrCat("texture ", sha256, ": ", entry.status().message(), "; upload it again"));
  }
  return absl::NotFoundError(absl::StrCat("texture ", sha256, " is not stored; upload it first"));
}

size_t TextureStore::size() const {
  std::lock_guard lock(mutex_);
  return textures_.size() + known_.size();
}

void TextureStore::SetBudget(uint64_t budget_bytes) {
  if (shared_) shared_->SetBudget(budget_bytes, "--max-store-mb");
  std::lock_guard lock(mutex_);
  budget_bytes_ = budget_bytes;
}

uint64_t TextureStore::evicted() const {
  if (shared_) return shared_->counters().evicted;
  std::lock_guard lock(mutex_);
  return evicted_;
}

uint64_t TextureStore::bytes() const {
  if (shared_) return shared_->TotalBytes();
  std::lock_guard lock(mutex_);
  uint64_t total = 0;
  for (const auto& [sha256, upload] : textures_) total += upload.bytes->size();
  return total;
}

uint64_t TextureStore::Trim(uint64_t budget_bytes) {
  if (shared_) {
    const StoreTrim trim = shared_->Trim(budget_bytes);
    if (trim.entries_evicted > 0) {
      std::lock_guard lock(mutex_);
      std::erase_if(known_, [&](const std::string& sha256) {
        return !shared_->Has(KeyOf(sha256), EntryKind::kBlob);
      });
    }
    return trim.entries_evicted;
  }
  std::lock_guard lock(mutex_);
  uint64_t total = 0, evicted = 0;
  for (const auto& [sha256, upload] : textures_) total += upload.bytes->size();
  while (total > budget_bytes && !textures_.empty()) {
    auto oldest = textures_.begin();
    for (auto it = textures_.begin(); it != textures_.end(); ++it)
      if (it->second.last_use < oldest->second.last_use) oldest = it;
    total -= oldest->second.bytes->size();
    textures_.erase(oldest);
    ++evicted;
  }
  evicted_ += evicted;
  return evicted;
}

}  // namespace aperture
