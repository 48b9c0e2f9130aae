#include "texture/summed_area_levels.h"

#include <algorithm>
#include <cstdint>
#include <cstring>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "texture/texture_entries.h"

namespace aperture {
namespace {

constexpr char kMagic[8] = {'A', 'P', 'S', 'A', 'T', 'L', 'v', 0};
struct LevelsHeader {
  char magic[8];
  uint32_t version;
  int32_t levels;
  uint32_t reserved[4];
};
static_assert(sizeof(LevelsHeader) == 32);
constexpr int kMaxLevels = 32;

size_t RoundUp8(size_t n) { return (n + 7) & ~size_t{7}; }

// Where each level's block lies in the levels block (offset, size per level), and its total size:
// known from the levels' sizes alone, before any table is built.
struct LevelsLayout {
  std::vector<uint64_t> index;
  size_t total = 0;
};

LevelsLayout LayOut(const MipPyramid& pyramid, int channels) {
  LevelsLayout layout;
  const int levels = SummedAreaLevelCount(pyramid);
  size_t offset = RoundUp8(sizeof(LevelsHeader) + 2 * sizeof(uint64_t) * levels);
  for (int l = 0; l < levels; ++l) {
    const Image& level = pyramid.level(l);
    const size_t bytes = SummedAreaTable::BlockBytes(level.width(), level.height(), channels);
    layout.index.push_back(offset);
    layout.index.push_back(bytes);
    offset = RoundUp8(offset + bytes);
  }
  layout.total = offset;
  return layout;
}

}  // namespace

int SummedAreaLevelCount(const MipPyramid& pyramid) {
  int n = 0;
  while (n < pyramid.levels() &&
         (n == 0 || std::min(pyramid.level(n).width(), pyramid.level(n).height()) >= 2))
    ++n;
  return n;
}

std::vector<std::unique_ptr<SummedAreaTable>> BuildSummedAreaLevels(const MipPyramid& pyramid,
                                                                    int channels) {
  std::vector<std::unique_ptr<SummedAreaTable>> levels;
  for (int l = 0; l < SummedAreaLevelCount(pyramid); ++l)
    levels.push_back(std::make_unique<SummedAreaTable>(pyramid.level(l), channels));
  return levels;
}

std::vector<std::byte> SummedAreaLevelsToBytes(const MipPyramid& pyramid, int channels) {
  const LevelsLayout layout = LayOut(pyramid, channels);
  LevelsHeader h{};
  std::memcpy(h.magic, kMagic, sizeof(kMagic));
  h.version = kSummedAreaTableVersion;
  h.levels = static_cast<int32_t>(layout.index.size() / 2);
  std::vector<std::byte> out(layout.total);
  std::memcpy(out.data(), &h, sizeof(h));
  std::memcpy(out.data() + sizeof(h), layout.index.data(), layout.index.size() * sizeof(uint64_t));
  // One level's table at a time, written in place: the peak is the block and one table.
  for (int l = 0; l < h.levels; ++l)
    SummedAreaTable(pyramid.level(l), channels).WriteBlock(out.data() + layout.index[2 * l]);
  return out;
}

size_t SummedAreaLevelsBytes(const MipPyramid& pyramid, int channels) {
  return LayOut(pyramid, channels).total;
}

absl::StatusOr<std::vector<std::unique_ptr<SummedAreaTable>>> ViewSummedAreaLevels(
    std::span<const std::byte> block) {
  LevelsHeader h;
  if (block.size() < sizeof(h))
    return absl::DataLossError("summed-area tables block is shorter than its header");
  std::memcpy(&h, block.data(), sizeof(h));
  if (std::memcmp(h.magic, kMagic, sizeof(kMagic)) != 0 || h.version != kSummedAreaTableVersion)
    return absl::DataLossError("not a summed-area tables block of this version");
  if (h.levels < 1 || h.levels > kMaxLevels)
    return absl::DataLossError(absl::StrCat("summed-area tables block has ", h.levels, " levels"));
  const size_t index_bytes = 2 * sizeof(uint64_t) * h.levels;
  if (block.size() < sizeof(h) + index_bytes)
    return absl::DataLossError("summed-area tables block is shorter than its index");
  std::vector<uint64_t> index(2 * h.levels);
  std::memcpy(index.data(), block.data() + sizeof(h), index_bytes);
  std::vector<std::unique_ptr<SummedAreaTable>> levels;
  for (int l = 0; l < h.levels; ++l) {
    const uint64_t offset = index[2 * l], size = index[2 * l + 1];
    if (offset % 8 != 0 || offset < sizeof(h) + index_bytes || offset > block.size() ||
        size > block.size() - offset)
      return absl::DataLossError(
          absl::StrCat("summed-area tables block: level ", l, " lies outside the block"));
    auto view = SummedAreaTable::View(block.subspan(offset, size));
    if (!view.ok())
      return absl::Status(view.status().code(),
                          absl::StrCat("level ", l, ": ", view.status().message()));
    levels.push_back(*std::move(view));
  }
  return levels;
}

std::string SummedAreaTableKey(const MipPyramid& pyramid, int channels) {
  return absl::StrFormat("sat-v%d-c%d-%s", kSummedAreaTableVersion, channels,
                         ImageContentHash(pyramid.level(0)));
}

absl::StatusOr<std::shared_ptr<const StoreEntry>> GetOrBuildSummedAreaTables(
    const SharedStore& store, const MipPyramid& pyramid, int channels) {
  return store.GetOrBuild(
      SummedAreaTableKey(pyramid, channels), EntryKind::kSummedAreaTable,
      [&]() -> absl::StatusOr<std::vector<std::byte>> {
        return SummedAreaLevelsToBytes(pyramid, channels);
      },
      [](std::span<const std::byte> payload) { return ViewSummedAreaLevels(payload).status(); },
      SummedAreaLevelsBytes(pyramid, channels));
}

}  // namespace aperture
