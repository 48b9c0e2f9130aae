#include "store/shared_store.h"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <ctime>
#include <filesystem>

#include "absl/strings/match.h"
#include "absl/strings/str_cat.h"
#include "store/entry_file.h"

namespace aperture {
namespace {

namespace fs = std::filesystem;

constexpr char kEntrySuffix[] = ".entry";
constexpr char kTemporaryInfix[] = ".entry.tmp.";
constexpr uint64_t kEntryOverheadBytes = 4096;  // an entry's header and alignment

}  // namespace

StoreEntry::~StoreEntry() {
  if (mapping_) munmap(mapping_, mapping_bytes_);
}

absl::StatusOr<std::shared_ptr<SharedStore>> SharedStore::Open(const std::string& directory) {
  if (directory.empty()) return absl::InvalidArgumentError("store directory is empty");
  std::error_code error;
  fs::create_directories(directory, error);
  if (error)
    return absl::FailedPreconditionError(
        absl::StrCat("cannot create store directory ", directory, ": ", error.message()));
  if (access(directory.c_str(), W_OK | X_OK) != 0)
    return absl::PermissionDeniedError(
        absl::StrCat("store directory ", directory, " is not writable by this user"));
  std::shared_ptr<SharedStore> store(new SharedStore(directory));
  store->SweepTemporaries("");
  return store;
}

bool SharedStore::IsValidKey(const std::string& key) {
  if (key.empty() || key.size() > static_cast<size_t>(kMaxKeyLength) || key.front() == '.')
    return false;
  for (char c : key)
    if (!((c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '.' || c == '_' || c == '-'))
      return false;
  return true;
}

std::string SharedStore::EntryPath(const std::string& key) const {
  return (fs::path(directory_) / absl::StrCat(key, kEntrySuffix)).string();
}

// Each use marks the file used now: Trim evicts the least recently used first. The time is given,
// not left to the kernel, whose file times advance by clock ticks (a use right after another
// entry's publication would tie with it).
void SharedStore::MarkUsed(const std::string& path) {
  timespec now[2];
  ::clock_gettime(CLOCK_REALTIME, &now[0]);
  now[1] = now[0];
  ::utimensat(AT_FDCWD, path.c_str(), now, 0);
}

std::shared_ptr<const StoreEntry> SharedStore::Cached(const std::string& key) const {
  std::lock_guard lock(mutex_);
  auto it = mapped_.find(key);
  return it == mapped_.end() ? nullptr : it->second;
}

void SharedStore::Remember(const std::shared_ptr<const StoreEntry>& entry) const {
  std::lock_guard lock(mutex_);
  mapped_.emplace(entry->key(), entry);
}

void SharedStore::Forget(const std::string& key) const {
  std::lock_guard lock(mutex_);
  mapped_.erase(key);
}

absl::StatusOr<std::shared_ptr<const StoreEntry>> SharedStore::MapFile(const std::string& path,
                                                                       const std::string& key,
                                                                       EntryKind kind) const {
  auto file = MapEntryFile(path, key, kind);
  if (!file.ok()) return file.status();
  std::shared_ptr<StoreEntry> entry(new StoreEntry);
  entry->key_ = std::string(key);
  entry->kind_ = kind;
  entry->mapping_ = file->mapping;
  entry->mapping_bytes_ = file->bytes;
  entry->payload_ = file->payload;
  entry->build_ms_ = static_cast<double>(file->header->build_microseconds) / 1000.0;
  return std::shared_ptr<const StoreEntry>(std::move(entry));
}

absl::StatusOr<std::shared_ptr<const StoreEntry>> SharedStore::Attach(const std::string& key,
                                                                      EntryKind kind) const {
  if (!IsValidKey(key))
    return absl::InvalidArgumentError(absl::StrCat("bad store key '", key, "'"));
  auto mark_used = [&] { MarkUsed(EntryPath(key)); };
  if (auto cached = Cached(key)) {
    if (cached->kind() != kind)
      return absl::FailedPreconditionError(
          absl::StrCat("store entry ", key, " holds a ", EntryKindName(cached->kind())));
    mark_used();
    return cached;
  }
  auto entry = MapFile(EntryPath(key), key, kind);
  if (!entry.ok()) return entry.status();
  mark_used();
  attached_.fetch_add(1, std::memory_order_relaxed);
  Remember(*entry);
  return *entry;
}

absl::StatusOr<std::shared_ptr<const StoreEntry>> SharedStore::AttachValid(
    const std::string& key, EntryKind kind, const Validator& validate) const {
  auto entry = Attach(key, kind);
  if (!entry.ok() || !validate) return entry;
  if (absl::Status valid = validate((*entry)->payload()); !valid.ok()) {
    Forget(key);
    return absl::DataLossError(absl::StrCat(EntryPath(key), ": ", valid.message()));
  }
  return entry;
}

absl::StatusOr<std::shared_ptr<const StoreEntry>> SharedStore::GetOrBuild(
    const std::string& key, EntryKind kind, const Builder& build, const Validator& validate,
    uint64_t payload_bytes) const {
  auto entry = AttachValid(key, kind, validate);
  if (entry.ok() || (!absl::IsNotFound(entry.status()) && !absl::IsDataLoss(entry.status())))
    return entry;

  const std::string path = EntryPath(key);
  auto lock = KeyLock::Acquire((fs::path(directory_) / absl::StrCat(key, ".lock")).string(), true);
  if (!lock.ok()) return lock.status();
  // Another process may have published it while this one waited for the lock.
  entry = AttachValid(key, kind, validate);
  if (entry.ok() || (!absl::IsNotFound(entry.status()) && !absl::IsDataLoss(entry.status())))
    return entry;
  if (absl::IsDataLoss(entry.status())) {
    rejected_.fetch_add(1, std::memory_order_relaxed);
    unlink(path.c_str());
  }
  SweepTemporaries(key);
  if (payload_bytes > 0)
    if (absl::Status fits = CheckFitsBudget(payload_bytes); !fits.ok()) return fits;

  auto writer = EntryWriter::Begin(absl::StrCat(path, ".tmp.", getpid()), key, kind);
  if (!writer.ok()) return writer.status();
  const auto start = std::chrono::steady_clock::now();
  auto payload = build();
  if (!payload.ok()) return payload.status();
  const auto micros = std::chrono::duration_cast<std::chrono::microseconds>(
                          std::chrono::steady_clock::now() - start)
                          .count();
  {
    // Room first: within this process, trim and publish one entry at a time, so the store's
    // files never exceed the budget (other processes sharing the directory trim for themselves).
    std::lock_guard publishing(publish_mutex_);
    if (absl::Status fits = CheckFitsBudget(payload->size()); !fits.ok()) return fits;
    if (const uint64_t budget = budget_bytes_.load(); budget > 0)
      Trim(budget - (payload->size() + kEntryOverheadBytes));
    if (auto status = writer->Publish(*payload, static_cast<uint64_t>(micros), path); !status.ok())
      return status;
  }
  auto published = MapFile(path, key, kind);
  if (!published.ok()) return published.status();
  MarkUsed(path);
  built_.fetch_add(1, std::memory_order_relaxed);
  Remember(*published);
  // A freshly built entry its reader refuses is a bug of the builder: reported, not rebuilt.
  if (validate)
    if (absl::Status valid = validate((*published)->payload()); !valid.ok()) return valid;
  return *published;
}

void SharedStore::SetBudget(uint64_t budget_bytes, std::string setting) const {
  std::lock_guard lock(budget_mutex_);
  budget_bytes_ = budget_bytes;
  budget_setting_ = std::move(setting);
}

absl::Status SharedStore::CheckFitsBudget(uint64_t payload_bytes) const {
  const uint64_t budget = budget_bytes_.load();
  if (budget == 0 || payload_bytes + kEntryOverheadBytes <= budget) return absl::OkStatus();
  std::lock_guard lock(budget_mutex_);
  return absl::ResourceExhaustedError(absl::StrCat(
      "an entry of ", payload_bytes >> 20, " MiB does not fit in the texture store's budget of ",
      budget >> 20, " MiB", budget_setting_.empty() ? "" : " (" + budget_setting_ + ")"));
}

absl::StatusOr<std::shared_ptr<const StoreEntry>> SharedStore::Put(
    const std::string& key, EntryKind kind, std::span<const std::byte> payload) const {
  return GetOrBuild(key, kind, [&]() -> absl::StatusOr<std::vector<std::byte>> {
    return std::vector<std::byte>(payload.begin(), payload.end());
  });
}

bool SharedStore::Has(const std::string& key, EntryKind kind) const {
  return Attach(key, kind).ok();
}

void SharedStore::SweepTemporaries(const std::string& only_key) const {
  std::error_code error;
  for (const auto& item : fs::directory_iterator(directory_, error)) {
    const std::string name = item.path().filename().string();
    const size_t infix = name.find(kTemporaryInfix);
    if (infix == std::string::npos || infix == 0) continue;
    const std::string key = name.substr(0, infix);
    if (!only_key.empty()) {
      // The caller holds this key's lock: whoever wrote the file is gone.
      if (key == only_key) fs::remove(item.path(), error);
      continue;
    }
    auto lock = KeyLock::Acquire((fs::path(directory_) / absl::StrCat(key, ".lock")).string(),
                                 /*wait=*/false);
    if (lock.ok()) fs::remove(item.path(), error);  // its builder died mid-build
  }
}

uint64_t SharedStore::TotalBytes() const {
  // No entry of this process is written while they are counted (files deleted meanwhile are
  // counted or not; none is counted twice), so the figure is one the store really had.
  std::lock_guard publishing(publish_mutex_);
  uint64_t total = 0;
  std::error_code error;
  for (const auto& item : fs::directory_iterator(directory_, error)) {
    const std::string name = item.path().filename().string();
    if (absl::EndsWith(name, kEntrySuffix) || name.find(kTemporaryInfix) != std::string::npos) {
      const uint64_t bytes = item.is_regular_file(error) ? item.file_size(error) : 0;
      if (!error) total += bytes;
    }
  }
  return total;
}

StoreTrim SharedStore::Trim(uint64_t budget_bytes) const {
  struct Candidate {
    fs::file_time_type used;
    uint64_t bytes;
    fs::path path;
    std::string key;
  };
  StoreTrim trim;
  std::vector<Candidate> published;
  std::error_code error;
  for (const auto& item : fs::directory_iterator(directory_, error)) {
    const std::string name = item.path().filename().string();
    std::error_code item_error;
    const uint64_t bytes = item.is_regular_file(item_error) ? item.file_size(item_error) : 0;
    if (item_error) continue;  // deleted meanwhile by another process
    if (name.find(kTemporaryInfix) != std::string::npos) {
      trim.bytes_before += bytes;
    } else if (absl::EndsWith(name, kEntrySuffix)) {
      trim.bytes_before += bytes;
      const auto used = item.last_write_time(item_error);
      if (!item_error)
        published.push_back(
            {used, bytes, item.path(), name.substr(0, name.size() - std::strlen(kEntrySuffix))});
    }
  }
  trim.bytes_after = trim.bytes_before;
  if (trim.bytes_before <= budget_bytes) return trim;
  std::sort(published.begin(), published.end(),
            [](const Candidate& a, const Candidate& b) { return a.used < b.used; });
  for (const Candidate& c : published) {
    if (trim.bytes_after <= budget_bytes) break;
    if (!fs::remove(c.path, error) || error) continue;  // gone already, or not ours to delete
    trim.bytes_after -= c.bytes;
    ++trim.entries_evicted;
    std::lock_guard lock(mutex_);
    mapped_.erase(c.key);
  }
  evicted_.fetch_add(trim.entries_evicted, std::memory_order_relaxed);
  return trim;
}

std::vector<StoreEntryInfo> SharedStore::List() const {
  std::vector<StoreEntryInfo> entries;
  std::error_code error;
  for (const auto& item : fs::directory_iterator(directory_, error)) {
    const std::string name = item.path().filename().string();
    StoreEntryInfo info;
    info.file = item.path().string();
    info.bytes = item.is_regular_file(error) ? item.file_size(error) : 0;
    if (const size_t infix = name.find(kTemporaryInfix); infix != std::string::npos) {
      info.key = name.substr(0, infix);
      info.state = "building (or left by a crashed builder)";
    } else if (absl::EndsWith(name, kEntrySuffix)) {
      info.key = name.substr(0, name.size() - std::strlen(kEntrySuffix));
      // Any kind: read the header's kind by trying each.
      info.state = "unreadable";
      for (EntryKind kind : {EntryKind::kBlob, EntryKind::kPrefilteredTable,
                             EntryKind::kPackedTexture, EntryKind::kSummedAreaTable}) {
        auto file = MapEntryFile(info.file, info.key, kind);
        if (file.ok()) {
          info.state = absl::StrCat("complete ", EntryKindName(kind));
          UnmapEntryFile(*file);
          break;
        }
        if (!absl::IsFailedPrecondition(file.status())) {
          info.state = std::string(file.status().message());
          break;
        }
      }
    } else {
      continue;
    }
    entries.push_back(std::move(info));
  }
  std::sort(entries.begin(), entries.end(),
            [](const StoreEntryInfo& a, const StoreEntryInfo& b) { return a.file < b.file; });
  return entries;
}

StoreCounters SharedStore::counters() const {
  return {attached_.load(), built_.load(), rejected_.load(), evicted_.load()};
}

}  // namespace aperture
