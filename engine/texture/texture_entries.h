// The textures the engine keeps in the shared store (store/shared_store.h): seed 000 tables and
// seed 001 packed textures, each keyed by a hash of its source so that every process (and a
// restarted server) finds the entry another built; each got from the store or built into it.
// Seed 003's summed-area tables, a texture prefilter too, keep their key and version with their
// format (texture/summed_area_table.h).
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <string>

#include "absl/status/statusor.h"
#include "base/image.h"
#include "store/shared_store.h"

namespace aperture {

// XXH3-128 of an image's size and texels, as 32 hex digits: what the keys below name a raster
// texture by.
std::string ImageContentHash(const Image& image);

// "table-v<table version>-<XXH3-128 of the power-of-two image's size and texels>".
std::string PrefilteredTableKey(const Image& base);
// "packed-v<format version>-<XXH3-128 of the .apv bytes>".
std::string PackedTextureKey(std::span<const uint8_t> apv_bytes);

// The table of `base` (a 2^n x 2^n image), built with BuildPrefilteredTable when the store has
// none; the payload is a block PrefilteredTable::View accepts.
// `stop`, when given, can stop the build (Cancelled; nothing is published).
absl::StatusOr<std::shared_ptr<const StoreEntry>> GetOrBuildPrefilteredTable(
    const SharedStore& store, const Image& base, const std::function<bool()>& stop = nullptr);

// The in-memory packed texture decoded from .apv bytes; the payload is what
// packed::PackedTextureView::FromBytes accepts.
absl::StatusOr<std::shared_ptr<const StoreEntry>> GetOrDecodePackedTexture(
    const SharedStore& store, std::span<const uint8_t> apv_bytes);

}  // namespace aperture
