#include "texture/texture_entries.h"

#include <xxhash.h>

#include <cstring>

#include "absl/strings/str_format.h"
#include "texture/packed/apv_file.h"
#include "texture/packed/packed_texture.h"
#include "texture/prefiltered_table.h"
#include "texture/prefiltered_table_builder.h"

namespace aperture {
namespace {

std::string Hex(XXH128_hash_t hash) {
  return absl::StrFormat("%016x%016x", hash.high64, hash.low64);
}

std::vector<std::byte> ToBytes(std::span<const uint8_t> bytes) {
  std::vector<std::byte> out(bytes.size());
  if (!bytes.empty()) std::memcpy(out.data(), bytes.data(), bytes.size());
  return out;
}

}  // namespace

std::string ImageContentHash(const Image& base) {
  XXH3_state_t* state = XXH3_createState();
  XXH3_128bits_reset(state);
  const int32_t size[2] = {base.width(), base.height()};
  XXH3_128bits_update(state, size, sizeof(size));
  XXH3_128bits_update(state, base.texels().data(), base.texels().size_bytes());
  const XXH128_hash_t hash = XXH3_128bits_digest(state);
  XXH3_freeState(state);
  return Hex(hash);
}

std::string PrefilteredTableKey(const Image& base) {
  return absl::StrFormat("table-v%d-%s", kTableVersion, ImageContentHash(base));
}

std::string PackedTextureKey(std::span<const uint8_t> apv_bytes) {
  return absl::StrFormat("packed-v%d-%s", packed::kPackedVersion,
                         Hex(XXH3_128bits(apv_bytes.data(), apv_bytes.size())));
}

absl::StatusOr<std::shared_ptr<const StoreEntry>> GetOrBuildPrefilteredTable(
    const SharedStore& store, const Image& base, const std::function<bool()>& stop) {
  return store.GetOrBuild(
      PrefilteredTableKey(base), EntryKind::kPrefilteredTable,
      [&]() -> absl::StatusOr<std::vector<std::byte>> {
        TableBuildOptions options;
        options.stop = stop;
        auto block = BuildPrefilteredTable(base, options);
        if (!block.ok()) return block.status();
        return std::move(block->bytes);
      },
      // The store vouches for the bytes; the table's own checks catch a foreign writer (a build
      // with another layout).
      [](std::span<const std::byte> payload) { return PrefilteredTable::View(payload).status(); });
}

absl::StatusOr<std::shared_ptr<const StoreEntry>> GetOrDecodePackedTexture(
    const SharedStore& store, std::span<const uint8_t> apv_bytes) {
  return store.GetOrBuild(
      PackedTextureKey(apv_bytes), EntryKind::kPackedTexture,
      [&]() -> absl::StatusOr<std::vector<std::byte>> {
        auto texture = packed::DecodeApv(apv_bytes);
        if (!texture.ok()) return texture.status();
        return ToBytes(texture->bytes());
      },
      [](std::span<const std::byte> payload) {
        return packed::PackedTextureView::FromBytes(
                   {reinterpret_cast<const uint8_t*>(payload.data()), payload.size()})
            .status();
      });
}

}  // namespace aperture
