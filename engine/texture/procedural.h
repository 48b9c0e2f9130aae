// Procedural textures for built-in scenes: tileable value noise tinted as grass or asphalt.
#pragma once

#include <cstdint>
#include <vector>

#include "absl/status/statusor.h"
#include "base/image.h"

namespace aperture {

// Periodic (tileable) multi-octave value noise in [0, 1], `size` a power of two.
Image MakeNoiseTexture(int size, uint32_t seed, Rgba dark, Rgba light);

// Encodes an image as 8-bit PNG bytes (values clamped to [0, 1], stored linearly) at zlib level
// 0 (stored) .. 9 (smallest). An image with any alpha below 1 is written RGBA, its colours taken
// as PNG's unassociated ones (decoding premultiplies them); otherwise RGB.
absl::StatusOr<std::vector<uint8_t>> EncodePng(const Image& image, int zlib_level = 6);

}  // namespace aperture
