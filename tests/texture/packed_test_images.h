// Generated palette images for the packed-texture tests.
#pragma once

#include <cstdint>
#include <random>

#include "texture/packed/palette.h"

namespace aperture::packed::testing {

// `colours` palette entries; each texel random (noise) or, with `blocky`, random rectangles
// painted over a background so that runs are long as in map textures.
inline IndexedImage RandomIndexedImage(uint32_t width, uint32_t height, uint32_t colours,
                                       uint64_t seed, bool blocky = false) {
  std::mt19937_64 rng(seed);
  IndexedImage image;
  image.width = width;
  image.height = height;
  for (uint32_t i = 0; i < colours; ++i)
    image.palette.push_back(PackRgba8(static_cast<uint8_t>(i), static_cast<uint8_t>(255 - i),
                                      static_cast<uint8_t>(i * 37),
                                      static_cast<uint8_t>(255 - i / 2)));
  image.indices.resize(size_t{width} * height);
  if (!blocky) {
    for (uint8_t& p : image.indices) p = static_cast<uint8_t>(rng() % colours);
    return image;
  }
  const int rects = 3 + static_cast<int>((size_t{width} * height) / 400);
  for (int r = 0; r < rects; ++r) {
    const uint32_t x0 = rng() % width, y0 = rng() % height;
    const uint32_t x1 = x0 + 1 + rng() % (width - x0), y1 = y0 + 1 + rng() % (height - y0);
    const uint8_t p = static_cast<uint8_t>(rng() % colours);
    for (uint32_t y = y0; y < y1; ++y)
      for (uint32_t x = x0; x < x1; ++x) image.indices[size_t{y} * width + x] = p;
  }
  return image;
}

}  // namespace aperture::packed::testing
