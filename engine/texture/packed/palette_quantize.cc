#include "texture/packed/palette_quantize.h"

#include <algorithm>
#include <unordered_map>

namespace aperture::packed {
namespace {

struct WeightedColour {
  uint32_t rgba;
  uint64_t count;
};

struct Box {
  size_t begin, end;  // range in the colour list
  int widest_channel;
  int extent;
};

Box MakeBox(const std::vector<WeightedColour>& colours, size_t begin, size_t end) {
  Box box{begin, end, 0, -1};
  for (int c = 0; c < 4; ++c) {
    int lo = 255, hi = 0;
    for (size_t i = begin; i < end; ++i) {
      lo = std::min<int>(lo, Channel(colours[i].rgba, c));
      hi = std::max<int>(hi, Channel(colours[i].rgba, c));
    }
    if (hi - lo > box.extent) {
      box.extent = hi - lo;
      box.widest_channel = c;
    }
  }
  return box;
}

}  // namespace

std::vector<uint32_t> MedianCutPalette(const Rgba8Image& image, uint32_t max_colours) {
  std::unordered_map<uint32_t, uint64_t> counts;
  for (uint32_t t : image.texels) ++counts[t];
  std::vector<WeightedColour> colours;
  colours.reserve(counts.size());
  for (const auto& [rgba, count] : counts) colours.push_back({rgba, count});
  std::vector<Box> boxes = {MakeBox(colours, 0, colours.size())};
  // Split the box with the widest channel extent at its weighted median until there are enough.
  while (boxes.size() < max_colours) {
    auto widest = std::max_element(boxes.begin(), boxes.end(),
                                   [](const Box& a, const Box& b) { return a.extent < b.extent; });
    if (widest->extent <= 0) break;
    const Box box = *widest;
    const int c = box.widest_channel;
    std::sort(colours.begin() + box.begin, colours.begin() + box.end,
              [c](const WeightedColour& a, const WeightedColour& b) {
                return Channel(a.rgba, c) < Channel(b.rgba, c);
              });
    uint64_t total = 0;
    for (size_t i = box.begin; i < box.end; ++i) total += colours[i].count;
    uint64_t running = 0;
    size_t split = box.begin + 1;
    for (size_t i = box.begin; i + 1 < box.end; ++i) {
      running += colours[i].count;
      split = i + 1;
      if (2 * running >= total) break;
    }
    *widest = MakeBox(colours, box.begin, split);
    boxes.push_back(MakeBox(colours, split, box.end));
  }
  // Each box's colour: the count-weighted mean.
  std::vector<uint32_t> palette;
  for (const Box& box : boxes) {
    uint64_t sum[4] = {0, 0, 0, 0}, total = 0;
    for (size_t i = box.begin; i < box.end; ++i) {
      for (int c = 0; c < 4; ++c) sum[c] += Channel(colours[i].rgba, c) * colours[i].count;
      total += colours[i].count;
    }
    uint8_t mean[4];
    for (int c = 0; c < 4; ++c) mean[c] = static_cast<uint8_t>((sum[c] + total / 2) / total);
    palette.push_back(PackRgba8(mean[0], mean[1], mean[2], mean[3]));
  }
  std::sort(palette.begin(), palette.end());
  palette.erase(std::unique(palette.begin(), palette.end()), palette.end());
  return palette;
}

std::vector<uint8_t> NearestPaletteIndices(const Rgba8Image& image,
                                           const std::vector<uint32_t>& palette) {
  std::unordered_map<uint32_t, uint8_t> memo;
  std::vector<uint8_t> indices(image.texels.size());
  for (size_t i = 0; i < image.texels.size(); ++i) {
    const uint32_t t = image.texels[i];
    auto it = memo.find(t);
    if (it == memo.end()) {
      int best = 0;
      int64_t best_distance = INT64_MAX;
      for (size_t p = 0; p < palette.size(); ++p) {
        int64_t d = 0;
        for (int c = 0; c < 4; ++c) {
          const int64_t diff = int64_t{Channel(t, c)} - Channel(palette[p], c);
          d += diff * diff;
        }
        if (d < best_distance) {
          best_distance = d;
          best = static_cast<int>(p);
        }
      }
      it = memo.emplace(t, static_cast<uint8_t>(best)).first;
    }
    indices[i] = it->second;
  }
  return indices;
}

}  // namespace aperture::packed
