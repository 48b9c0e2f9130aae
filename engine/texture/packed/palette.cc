#include "texture/packed/palette.h"

#include <unordered_map>

#include "absl/strings/str_cat.h"
#include "texture/packed/palette_quantize.h"

namespace aperture::packed {
namespace {

// Maps each texel to its palette entry; false when a texel's colour is not in `palette`.
bool IndexTexels(const Rgba8Image& image, const std::vector<uint32_t>& palette,
                 std::vector<uint8_t>& indices) {
  std::unordered_map<uint32_t, uint8_t> lookup;
  for (size_t i = 0; i < palette.size(); ++i) lookup.emplace(palette[i], static_cast<uint8_t>(i));
  indices.resize(image.texels.size());
  uint32_t last_colour = 0;
  uint8_t last_index = 0;
  bool have_last = false;
  for (size_t i = 0; i < image.texels.size(); ++i) {
    const uint32_t t = image.texels[i];
    if (!have_last || t != last_colour) {
      auto it = lookup.find(t);
      if (it == lookup.end()) return false;
      last_colour = t;
      last_index = it->second;
      have_last = true;
    }
    indices[i] = last_index;
  }
  return true;
}

}  // namespace

absl::StatusOr<IndexedImage> BuildPalette(const Rgba8Image& image, bool quantize) {
  if (image.width == 0 || image.height == 0 ||
      image.texels.size() != size_t{image.width} * image.height)
    return absl::InvalidArgumentError("image has no texels");
  IndexedImage out;
  out.width = image.width;
  out.height = image.height;
  // Distinct colours in order of first appearance; stop counting well past the limit.
  std::unordered_map<uint32_t, uint32_t> seen;
  uint32_t previous = ~image.texels[0];
  for (uint32_t t : image.texels) {
    if (t == previous) continue;
    previous = t;
    if (seen.emplace(t, static_cast<uint32_t>(seen.size())).second && !quantize &&
        seen.size() > kMaxPaletteSize)
      return absl::InvalidArgumentError(absl::StrCat(
          "image has more than ", kMaxPaletteSize,
          " distinct colours; a packed texture holds at most 256 (use --quantize to reduce it)"));
  }
  if (seen.size() <= kMaxPaletteSize) {
    out.palette.resize(seen.size());
    for (const auto& [colour, index] : seen) out.palette[index] = colour;
  } else {
    out.palette = MedianCutPalette(image, kMaxPaletteSize);
  }
  if (IndexTexels(image, out.palette, out.indices)) return out;
  // Quantized: each texel takes its nearest palette colour.
  out.indices = NearestPaletteIndices(image, out.palette);
  return out;
}

Rgba8Image ExpandPalette(const IndexedImage& image) {
  Rgba8Image out;
  out.width = image.width;
  out.height = image.height;
  out.texels.resize(image.indices.size());
  for (size_t i = 0; i < image.indices.size(); ++i) out.texels[i] = image.palette[image.indices[i]];
  return out;
}

}  // namespace aperture::packed
