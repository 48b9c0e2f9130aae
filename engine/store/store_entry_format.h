// The on-disk (shared-memory) form of one texture-store entry: a fixed header at offset 0, then
// the payload (a prefiltered table, a packed texture, an uploaded image) at `payload_offset`. No
// pointers, only offsets, so every process maps the same bytes read-only and uses them in place.
//
// An entry is written under a temporary name with `complete` = 0, the payload and its checksum
// first, `complete` = kCompleteMark last, then renamed to its final name. A reader uses an entry
// only when the magic, version, sizes, completion mark and checksum all hold, so an entry cut
// short by a crash is never used.
#pragma once

#include <cstdint>

namespace aperture {

inline constexpr char kStoreMagic[8] = {'A', 'P', 'S', 'T', 'O', 'R', 'E', '1'};
inline constexpr uint32_t kStoreVersion = 1;
inline constexpr uint32_t kCompleteMark = 0x454e4f44;  // "DONE"
// Payloads start on a cache line, which satisfies every payload's own alignment (8 bytes).
inline constexpr uint64_t kPayloadAlignment = 64;
inline constexpr int kMaxKeyLength = 120;

enum class EntryKind : uint32_t {
  kBlob = 1,              // uploaded bytes, as they came (an encoded image or an .apv file)
  kPrefilteredTable = 2,  // seed 000's table block (texture/prefiltered_table.h)
  kPackedTexture = 3,     // seed 001's in-memory packed texture (texture/packed/packed_texture.h)
  kSummedAreaTable = 4,   // seed 003's summed-area tables (texture/summed_area_table.h)
};

const char* EntryKindName(EntryKind kind);

struct StoreEntryHeader {
  char magic[8];
  uint32_t version;
  uint32_t header_bytes;  // sizeof(StoreEntryHeader)
  uint32_t kind;          // EntryKind
  uint32_t complete;      // kCompleteMark once everything else is written
  uint64_t payload_offset;
  uint64_t payload_bytes;
  uint64_t checksum;  // XXH3-64 of the payload
  uint64_t build_microseconds;
  char key[kMaxKeyLength + 8];  // NUL-terminated
};
static_assert(sizeof(StoreEntryHeader) == 184);
static_assert(sizeof(StoreEntryHeader) <= 192, "payload offset is the header rounded to 64");

}  // namespace aperture
