// What the engine keeps in the shared store (shared_store.h): seed 000 tables, seed 001 packed
// textures and seed 003's summed-area tables, each keyed by a hash of its source so that every
// process (and a restarted server) finds the entry another built.
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

// "table-v<table version>-<XXH3-128 of the power-of-two image's size and texels>".
std::string PrefilteredTableKey(const Image& base);
// "sat-v<block version>-c<channels>-<XXH3-128 of the image's size and texels>".
std::string SummedAreaTableKey(const Image& base, int channels);
// "packed-v<format version>-<XXH3-128 of the .apv bytes>".
std::string PackedTextureKey(std::span<const uint8_t> apv_bytes);

// The table of `base` (a 2^n x 2^n image), built with BuildPrefilteredTable when the store has
// none; the payload is a block PrefilteredTable::View accepts.
// `stop`, when given, can stop the build (Cancelled; nothing is published).
absl::StatusOr<std::shared_ptr<const StoreEntry>> GetOrBuildPrefilteredTable(
    const SharedStore& store, const Image& base, const std::function<bool()>& stop = nullptr);

// The summed-area tables of `base` (`channels` = 3 or 4), built when the store has none; the
// payload is a block SummedAreaTable::View accepts.
absl::StatusOr<std::shared_ptr<const StoreEntry>> GetOrBuildSummedAreaTable(
    const SharedStore& store, const Image& base, int channels);

// The in-memory packed texture decoded from .apv bytes; the payload is what
// packed::PackedTextureView::FromBytes accepts.
absl::StatusOr<std::shared_ptr<const StoreEntry>> GetOrDecodePackedTexture(
    const SharedStore& store, std::span<const uint8_t> apv_bytes);

}  // namespace aperture
