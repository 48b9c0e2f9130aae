// Colour quantization for images with more than 256 colours (seed 001, section 2.2: the texture
// is first "brought to the required type (256 colours, 24-bit colour)").
#pragma once

#include <cstdint>
#include <vector>

#include "texture/packed/rgba8_image.h"

namespace aperture::packed {

// Median cut (Heckbert 1982) over RGBA, weighted by texel counts: at most `max_colours` entries.
std::vector<uint32_t> MedianCutPalette(const Rgba8Image& image, uint32_t max_colours);

// Each texel's nearest palette entry (squared RGBA distance).
std::vector<uint8_t> NearestPaletteIndices(const Rgba8Image& image,
                                           const std::vector<uint32_t>& palette);

}  // namespace aperture::packed
