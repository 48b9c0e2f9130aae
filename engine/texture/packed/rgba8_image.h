// 8-bit RGBA images as OpenImageIO reads them, for exact palettes (no float round trip).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "absl/status/status.h"
#include "absl/status/statusor.h"

namespace aperture::packed {

// A colour as 4 bytes r, g, b, a (r in the low byte).
inline uint32_t PackRgba8(uint8_t r, uint8_t g, uint8_t b, uint8_t a) {
  return uint32_t{r} | (uint32_t{g} << 8) | (uint32_t{b} << 16) | (uint32_t{a} << 24);
}
inline uint8_t Channel(uint32_t rgba, int c) { return static_cast<uint8_t>(rgba >> (8 * c)); }

struct Rgba8Image {
  uint32_t width = 0, height = 0;
  std::vector<uint32_t> texels;  // row-major, row 0 first
  uint32_t at(uint32_t x, uint32_t y) const { return texels[size_t{y} * width + x]; }
};

// Any image OpenImageIO reads, converted to 8 bits per channel; grey becomes grey RGB, missing
// alpha becomes 255. Refuses sides above 65536 (seed 001, section 2.5).
absl::StatusOr<Rgba8Image> LoadRgba8Image(const std::string& path);
// Writes RGBA, or RGB when every alpha is 255.
absl::Status WriteRgba8Image(const Rgba8Image& image, const std::string& path);

}  // namespace aperture::packed
