// The palette image a packed texture is made from (seed 001, section 2.2: "256 colours, 24-bit
// colour"; we keep alpha as a fourth byte so that cut-outs survive).
#pragma once

#include <cstdint>
#include <vector>

#include "absl/status/statusor.h"
#include "texture/packed/rgba8_image.h"

namespace aperture::packed {

inline constexpr uint32_t kMaxPaletteSize = 256;

struct IndexedImage {
  uint32_t width = 0, height = 0;
  std::vector<uint32_t> palette;  // RGBA8 (PackRgba8), at most 256 entries
  std::vector<uint8_t> indices;   // row-major palette indices
  uint8_t at(uint32_t x, uint32_t y) const { return indices[size_t{y} * width + x]; }
};

// The exact palette: colours in order of first appearance (row-major). Refuses an image with more
// than 256 distinct colours, naming the count, unless `quantize` asks for a 256-colour
// quantization (median cut, palette_quantize.h).
absl::StatusOr<IndexedImage> BuildPalette(const Rgba8Image& image, bool quantize = false);

// Back to colours.
Rgba8Image ExpandPalette(const IndexedImage& image);

}  // namespace aperture::packed
