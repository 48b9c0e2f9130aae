// The texture store shared by every server process on a machine: a directory of entry
// files, by default under /dev/shm (POSIX shared memory), each mapped read-only and used in place.
//
//   <key>.entry            a published entry (store_entry_format.h)
//   <key>.entry.tmp.<pid>  an entry being built; renamed to <key>.entry when complete
//   <key>.lock             flock(2) held while <key> is built, so it is built once per machine
//
// Building takes the key's lock, builds, writes the temporary entry, marks it complete and renames
// it: readers see a whole entry or none. The lock dies with its process, so a crash mid-build
// leaves only a temporary file, which the next builder of that key (or Open's sweep) deletes.
#pragma once

#include <atomic>
#include <cstddef>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "absl/status/statusor.h"
#include "store/store_entry_format.h"

namespace aperture {

inline constexpr char kDefaultStoreDirectory[] = "/dev/shm/aperture";

// A mapped, verified entry; unmapped when the last reference goes.
class StoreEntry {
 public:
  StoreEntry(const StoreEntry&) = delete;
  StoreEntry& operator=(const StoreEntry&) = delete;
  ~StoreEntry();

  const std::string& key() const { return key_; }
  EntryKind kind() const { return kind_; }
  std::span<const std::byte> payload() const { return payload_; }
  double build_ms() const { return build_ms_; }

 private:
  friend class SharedStore;
  StoreEntry() = default;

  std::string key_;
  EntryKind kind_ = EntryKind::kBlob;
  void* mapping_ = nullptr;
  size_t mapping_bytes_ = 0;
  std::span<const std::byte> payload_;
  double build_ms_ = 0;
};

// What a store directory holds, for `aperture-tex store` and the server's info.
struct StoreEntryInfo {
  std::string key;
  std::string file;
  uint64_t bytes = 0;
  std::string state;  // "complete", "building", or why the entry is unusable
};

// What Trim did.
struct StoreTrim {
  uint64_t bytes_before = 0, bytes_after = 0;
  uint64_t entries_evicted = 0;
};

struct StoreCounters {
  uint64_t attached = 0;  // entries mapped as they were (built before, maybe by another process)
  uint64_t built = 0;     // entries this process built and published
  uint64_t rejected = 0;  // half-written or corrupt entries found, never used (then rebuilt)
  uint64_t evicted = 0;   // entries this process deleted to keep the store within its budget
};

class SharedStore {
 public:
  using Builder = std::function<absl::StatusOr<std::vector<std::byte>>()>;
  // The reader's own check of an entry's payload (its format's version and layout): an entry the
  // store vouches for may still be one an older or foreign build wrote under the same key.
  using Validator = std::function<absl::Status(std::span<const std::byte>)>;

  // Creates the directory if needed and sweeps temporary files left by crashed builders.
  static absl::StatusOr<std::shared_ptr<SharedStore>> Open(const std::string& directory);

  const std::string& directory() const { return directory_; }

  // Keys: 1..kMaxKeyLength characters of [a-z0-9._-], not starting with '.'.
  static bool IsValidKey(const std::string& key);

  // Maps the published entry `key`. NotFound when there is none; DataLoss when it is half written
  // or corrupt (it is not used); FailedPrecondition when it holds another kind.
  absl::StatusOr<std::shared_ptr<const StoreEntry>> Attach(const std::string& key,
                                                           EntryKind kind) const;

  // Attaches, or, when the entry is missing or unusable, builds it once for the whole machine
  // (other processes wanting the same key wait, then attach) and publishes it. An entry that
  // `validate` (when given) refuses is unusable too: it is counted as rejected, deleted and
  // rebuilt (processes that have it mapped keep their pages). Every entry returned has passed
  // `validate`; one this call built and `validate` refuses is returned as validate's error.
  // `payload_bytes`, when the payload's size is known before building (0: not known): an entry
  // that cannot fit the budget is refused (ResourceExhausted naming both sizes) before `build`
  // runs, so a table of gigabytes is not built only to be thrown away.
  absl::StatusOr<std::shared_ptr<const StoreEntry>> GetOrBuild(const std::string& key,
                                                               EntryKind kind, const Builder& build,
                                                               const Validator& validate = nullptr,
                                                               uint64_t payload_bytes = 0) const;

  // Publishes `payload` unless a usable entry exists already.
  absl::StatusOr<std::shared_ptr<const StoreEntry>> Put(const std::string& key, EntryKind kind,
                                                        std::span<const std::byte> payload) const;

  bool Has(const std::string& key, EntryKind kind) const;
  std::vector<StoreEntryInfo> List() const;

  // Bytes of the directory's entry files (published and being built).
  uint64_t TotalBytes() const;
  // Deletes published entries, least recently used first (each Attach marks its file used, so the
  // order holds across processes), until the entry files take at most `budget_bytes`. A process
  // that has an entry mapped keeps it valid (the pages live until it unmaps them); this process
  // forgets its mapping, so the memory goes when its last user does. Entries being built stay.
  StoreTrim Trim(uint64_t budget_bytes) const;
  // With a budget (0: none), each entry this process publishes first trims the store to leave
  // room for it, and one larger than the budget is refused with ResourceExhausted; `setting`
  // names where the budget is set ("--max-store-mb"), for the message.
  void SetBudget(uint64_t budget_bytes, std::string setting = "") const;
  StoreCounters counters() const;

 private:
  // ResourceExhausted when an entry of `payload_bytes` cannot fit the budget.
  absl::Status CheckFitsBudget(uint64_t payload_bytes) const;
  explicit SharedStore(std::string directory) : directory_(std::move(directory)) {}

  std::string EntryPath(const std::string& key) const;
  absl::StatusOr<std::shared_ptr<const StoreEntry>> MapFile(const std::string& path,
                                                            const std::string& key,
                                                            EntryKind kind) const;
  absl::Status Publish(const std::string& key, EntryKind kind, std::span<const std::byte> payload,
                       uint64_t build_microseconds) const;
  void SweepTemporaries(const std::string& only_key) const;
  std::shared_ptr<const StoreEntry> Cached(const std::string& key) const;
  static void MarkUsed(const std::string& path);
  void Remember(const std::shared_ptr<const StoreEntry>& entry) const;
  void Forget(const std::string& key) const;
  // Attach, and an attached entry that `validate` refuses as DataLoss (and forgotten).
  absl::StatusOr<std::shared_ptr<const StoreEntry>> AttachValid(const std::string& key,
                                                                EntryKind kind,
                                                                const Validator& validate) const;

  std::string directory_;
  mutable std::mutex mutex_;
  // One mapping per key and process: attaching twice costs nothing and checksums once.
  mutable std::map<std::string, std::shared_ptr<const StoreEntry>, std::less<>> mapped_;
  mutable std::atomic<uint64_t> attached_{0}, built_{0}, rejected_{0}, evicted_{0};
  mutable std::atomic<uint64_t> budget_bytes_{0};
  mutable std::mutex budget_mutex_;
  mutable std::string budget_setting_;  // guarded by budget_mutex_
  mutable std::mutex publish_mutex_;
};

}  // namespace aperture
