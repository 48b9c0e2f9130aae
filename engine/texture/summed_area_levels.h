// The summed-area tables of a texture's mip levels, the base first (seed 003's integrals, and the
// coarser levels for projections too long to integrate on the base: trace/projection_integral),
// and their one shared-store entry per texture.
#pragma once

#include <memory>
#include <span>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "store/shared_store.h"
#include "texture/mip_pyramid.h"
#include "texture/summed_area_table.h"

namespace aperture {

// How many of the pyramid's levels are tabulated: the base, and every coarser one of at least 2
// texels on its shorter side.
int SummedAreaLevelCount(const MipPyramid& pyramid);

// The tables of those levels (`channels` = 1, 3 or 4), built here.
std::vector<std::unique_ptr<SummedAreaTable>> BuildSummedAreaLevels(const MipPyramid& pyramid,
                                                                    int channels);

// The levels as one block: a 32-byte header (magic, version, level count), each level's offset
// and size, then each level's own block (SummedAreaTable::ToBytes) at an 8-byte boundary.
std::vector<std::byte> SummedAreaLevelsToBytes(const MipPyramid& pyramid, int channels);
// The size of that block, from the levels' sizes alone (nothing is built): a 4096 x 4096 RGB
// texture's is about 4.3 GB.
size_t SummedAreaLevelsBytes(const MipPyramid& pyramid, int channels);
// Tables over such a block (8-byte aligned), which must outlive them; checks every bound.
absl::StatusOr<std::vector<std::unique_ptr<SummedAreaTable>>> ViewSummedAreaLevels(
    std::span<const std::byte> block);

// "sat-v<kSummedAreaTableVersion>-c<channels>-<XXH3-128 of the base's size and texels>": the
// shared store's name for the tables of `pyramid` (texture/texture_entries.h's ImageContentHash).
std::string SummedAreaTableKey(const MipPyramid& pyramid, int channels);

// The tables of `pyramid` (`channels` = 3 or 4) from the shared store, built into it when it has
// none; the payload is a block ViewSummedAreaLevels accepts. Tables larger than the store's
// budget are refused (ResourceExhausted) before they are built.
absl::StatusOr<std::shared_ptr<const StoreEntry>> GetOrBuildSummedAreaTables(
    const SharedStore& store, const MipPyramid& pyramid, int channels);

}  // namespace aperture
