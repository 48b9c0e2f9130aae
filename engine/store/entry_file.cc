#include "store/entry_file.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>
#include <xxhash.h>

#include <atomic>
#include <cerrno>
#include <cstring>

#include "absl/strings/str_cat.h"

namespace aperture {
namespace {

std::string ErrnoText() { return std::strerror(errno); }

uint64_t PayloadOffset() {
  return (sizeof(StoreEntryHeader) + kPayloadAlignment - 1) / kPayloadAlignment * kPayloadAlignment;
}

absl::Status WriteAll(int fd, const void* data, size_t bytes, uint64_t offset) {
  const char* p = static_cast<const char*>(data);
  while (bytes > 0) {
    const ssize_t written = pwrite(fd, p, bytes, static_cast<off_t>(offset));
    if (written < 0) {
      if (errno == EINTR) continue;
      // A full store is the client's problem to hear about, without the server's paths.
      if (errno == ENOSPC || errno == EDQUOT)
        return absl::ResourceExhaustedError(
            "the texture store is full (no space left on its file system)");
      return absl::InternalError(absl::StrCat("write: ", ErrnoText()));
    }
    p += written;
    bytes -= static_cast<size_t>(written);
    offset += static_cast<uint64_t>(written);
  }
  return absl::OkStatus();
}

}  // namespace

const char* EntryKindName(EntryKind kind) {
  switch (kind) {
    case EntryKind::kBlob:
      return "blob";
    case EntryKind::kPrefilteredTable:
      return "prefiltered-table";
    case EntryKind::kPackedTexture:
      return "packed-texture";
    case EntryKind::kSummedAreaTable:
      return "summed-area-table";
  }
  return "unknown";
}

absl::StatusOr<KeyLock> KeyLock::Acquire(const std::string& path, bool wait) {
  const int fd = open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd < 0) return absl::InternalError(absl::StrCat("cannot open ", path, ": ", ErrnoText()));
  int result;
  do {
    result = flock(fd, LOCK_EX | (wait ? 0 : LOCK_NB));
  } while (result != 0 && errno == EINTR);
  if (result != 0) {
    const bool busy = errno == EWOULDBLOCK;
    const std::string text = ErrnoText();
    close(fd);
    if (busy) return absl::UnavailableError(absl::StrCat(path, " is held by another builder"));
    return absl::InternalError(absl::StrCat("cannot lock ", path, ": ", text));
  }
  return KeyLock(fd);
}

KeyLock::~KeyLock() {
  if (fd_ >= 0) close(fd_);  // closing the last descriptor releases the flock
}

absl::StatusOr<EntryWriter> EntryWriter::Begin(std::string temporary_path, const std::string& key,
                                               EntryKind kind) {
  StoreEntryHeader header{};
  std::memcpy(header.magic, kStoreMagic, sizeof(header.magic));
  header.version = kStoreVersion;
  header.header_bytes = sizeof(StoreEntryHeader);
  header.kind = static_cast<uint32_t>(kind);
  header.complete = 0;
  header.payload_offset = PayloadOffset();
  if (key.size() > kMaxKeyLength) return absl::InvalidArgumentError("store key is too long");
  std::memcpy(header.key, key.data(), key.size());

  const int fd = open(temporary_path.c_str(), O_RDWR | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0)
    return absl::InternalError(
        absl::StrCat("cannot create store entry ", temporary_path, ": ", ErrnoText()));
  if (auto status = WriteAll(fd, &header, sizeof(header), 0); !status.ok()) {
    close(fd);
    unlink(temporary_path.c_str());
    return status;
  }
  return EntryWriter(fd, std::move(temporary_path), header);
}

EntryWriter::EntryWriter(EntryWriter&& other) noexcept
    : fd_(other.fd_), path_(std::move(other.path_)), header_(other.header_) {
  other.fd_ = -1;
}

EntryWriter::~EntryWriter() {
  if (fd_ < 0) return;
  close(fd_);
  unlink(path_.c_str());
}

absl::Status EntryWriter::Publish(std::span<const std::byte> payload, uint64_t build_microseconds,
                                  const std::string& final_path) {
  const uint64_t total = header_.payload_offset + payload.size();
  if (ftruncate(fd_, static_cast<off_t>(total)) != 0)
    return absl::ResourceExhaustedError(absl::StrCat(
        "the texture store has no room for an entry of ", total, " bytes (", ErrnoText(), ")"));
  if (auto status = WriteAll(fd_, payload.data(), payload.size(), header_.payload_offset);
      !status.ok())
    return absl::IsResourceExhausted(status)
               ? status
               : absl::Status(status.code(), absl::StrCat(path_, ": ", status.message()));

  header_.payload_bytes = payload.size();
  header_.checksum = XXH3_64bits(payload.data(), payload.size());
  header_.build_microseconds = build_microseconds;
  if (auto status = WriteAll(fd_, &header_, sizeof(header_), 0); !status.ok()) return status;
  // The completion mark goes last, after everything it vouches for.
  const uint32_t mark = kCompleteMark;
  if (auto status = WriteAll(fd_, &mark, sizeof(mark), offsetof(StoreEntryHeader, complete));
      !status.ok())
    return status;
  if (rename(path_.c_str(), final_path.c_str()) != 0)
    return absl::InternalError(
        absl::StrCat("cannot publish ", path_, " as ", final_path, ": ", ErrnoText()));
  close(fd_);
  fd_ = -1;
  return absl::OkStatus();
}

absl::StatusOr<MappedEntryFile> MapEntryFile(const std::string& path, const std::string& key,
                                             EntryKind kind) {
  const int fd = open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) {
    if (errno == ENOENT) return absl::NotFoundError(absl::StrCat(path, " does not exist"));
    return absl::InternalError(absl::StrCat("cannot open ", path, ": ", ErrnoText()));
  }
  struct stat info {};
  if (fstat(fd, &info) != 0) {
    close(fd);
    return absl::InternalError(absl::StrCat("cannot stat ", path, ": ", ErrnoText()));
  }
  const auto size = static_cast<size_t>(info.st_size);
  if (size < sizeof(StoreEntryHeader)) {
    close(fd);
    return absl::DataLossError(absl::StrCat(path, ": ", size, " bytes, shorter than a header"));
  }
  void* mapping = mmap(nullptr, size, PROT_READ, MAP_SHARED, fd, 0);
  close(fd);  // the mapping keeps the file
  if (mapping == MAP_FAILED)
    return absl::InternalError(absl::StrCat("cannot map ", path, ": ", ErrnoText()));

  MappedEntryFile file{mapping, size, static_cast<const StoreEntryHeader*>(mapping), {}};
  const StoreEntryHeader& h = *file.header;
  auto fail = [&](absl::Status status) {
    UnmapEntryFile(file);
    return status;
  };
  if (std::memcmp(h.magic, kStoreMagic, sizeof(h.magic)) != 0)
    return fail(absl::DataLossError(absl::StrCat(path, ": not a store entry (bad magic)")));
  if (h.version != kStoreVersion || h.header_bytes != sizeof(StoreEntryHeader))
    return fail(absl::DataLossError(absl::StrCat(path, ": store format version ", h.version,
                                                 ", this build reads ", kStoreVersion)));
  if (h.complete != kCompleteMark)
    return fail(absl::DataLossError(absl::StrCat(path, ": half written (not marked complete)")));
  if (h.payload_offset != PayloadOffset() || h.payload_offset > size ||
      h.payload_bytes != size - h.payload_offset)
    return fail(absl::DataLossError(absl::StrCat(path, ": payload of ", h.payload_bytes,
                                                 " bytes does not fit the file's ", size)));
  if (h.kind != static_cast<uint32_t>(kind))
    return fail(absl::FailedPreconditionError(
        absl::StrCat(path, " holds a ", EntryKindName(static_cast<EntryKind>(h.kind)), ", not a ",
                     EntryKindName(kind))));
  if (std::string_view(h.key, strnlen(h.key, sizeof(h.key))) != key)
    return fail(absl::FailedPreconditionError(absl::StrCat(path, " holds another key")));
  file.payload = {static_cast<const std::byte*>(mapping) + h.payload_offset, h.payload_bytes};
  if (XXH3_64bits(file.payload.data(), file.payload.size()) != h.checksum)
    return fail(absl::DataLossError(absl::StrCat(path, ": checksum mismatch (corrupt)")));
  return file;
}

void UnmapEntryFile(MappedEntryFile& file) {
  if (file.mapping) munmap(file.mapping, file.bytes);
  file = {};
}

}  // namespace aperture
