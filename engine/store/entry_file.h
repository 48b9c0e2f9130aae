// Low-level pieces of the shared store (shared_store.h): an exclusive per-key lock, the writer of
// a temporary entry that becomes a published one, and the read-only mapping of a published entry.
#pragma once

#include <cstddef>
#include <span>
#include <string>
#include <string_view>

#include "absl/status/statusor.h"
#include "store/store_entry_format.h"

namespace aperture {

// flock(2) on a lock file; released on destruction or when the process dies.
class KeyLock {
 public:
  // Blocks until the lock is held (`wait`), or returns Unavailable at once when another holds it.
  static absl::StatusOr<KeyLock> Acquire(const std::string& path, bool wait);
  KeyLock(KeyLock&& other) noexcept : fd_(other.fd_) { other.fd_ = -1; }
  KeyLock& operator=(KeyLock&&) = delete;
  ~KeyLock();

 private:
  explicit KeyLock(int fd) : fd_(fd) {}
  int fd_ = -1;
};

// A temporary entry file: created at once (header only, not complete) so a crash at any later
// point leaves an incomplete file, never a published entry. Removed on destruction unless
// published.
class EntryWriter {
 public:
  static absl::StatusOr<EntryWriter> Begin(std::string temporary_path, const std::string& key,
                                           EntryKind kind);
  EntryWriter(EntryWriter&& other) noexcept;
  EntryWriter& operator=(EntryWriter&&) = delete;
  ~EntryWriter();

  // Writes the payload and its checksum, marks the entry complete, renames it to `final_path`.
  absl::Status Publish(std::span<const std::byte> payload, uint64_t build_microseconds,
                       const std::string& final_path);

 private:
  EntryWriter(int fd, std::string path, StoreEntryHeader header)
      : fd_(fd), path_(std::move(path)), header_(header) {}
  int fd_ = -1;
  std::string path_;
  StoreEntryHeader header_{};
};

// A read-only mapping of a whole published entry, checked before anything trusts it.
struct MappedEntryFile {
  void* mapping = nullptr;
  size_t bytes = 0;
  const StoreEntryHeader* header = nullptr;
  std::span<const std::byte> payload;
};
// NotFound when the file does not exist; DataLoss, naming the fault, when the entry is cut short,
// not marked complete, or fails its checksum; FailedPrecondition for another kind or key.
absl::StatusOr<MappedEntryFile> MapEntryFile(const std::string& path, const std::string& key,
                                             EntryKind kind);
void UnmapEntryFile(MappedEntryFile& file);

}  // namespace aperture
