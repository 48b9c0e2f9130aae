// Image files as textures: OpenImageIO decodes them into a base/image.h Image (checked against the
// raster texture limit before any pixel is read) and resizes them to powers of two.
#pragma once

#include <cstdint>
#include <span>
#include <string>

#include "absl/status/statusor.h"
#include "base/image.h"

namespace aperture {

// The largest raster texture: 8192 x 8192 texels (1 GiB as float RGBA; its seed 000 table is
// 5.6 GB). Larger palette maps go in as packed vector textures (.apv, up to 65536 x 65536).
inline constexpr int64_t kMaxImageTexels = int64_t{8192} * 8192;

// Reads an image file through OpenImageIO. 8-bit values are taken as linear (value / 255).
// Greyscale becomes grey RGB, missing alpha becomes 1. Images of more than kMaxImageTexels
// texels are refused before their pixels are read.
absl::StatusOr<Image> LoadImageFile(const std::string& path);
// The same for an encoded image held in memory (PNG, JPEG, EXR, TIFF, ...).
absl::StatusOr<Image> DecodeImage(std::span<const uint8_t> bytes);

struct ImageHeader {
  int width = 0, height = 0, channels = 0;
  std::string format;  // OpenImageIO's name: "png", "openexr", ...
};
// The header of an encoded image, read without its pixels, with DecodeImage's checks (a known
// format, pixels present, at most kMaxImageTexels): what an upload or a scene's memory estimate
// needs to know before anything is decoded.
absl::StatusOr<ImageHeader> ReadImageHeader(std::span<const uint8_t> bytes);

// Resamples to the next power of two per side (OpenImageIO's default resize filter) when needed;
// returns the image unchanged otherwise.
Image ResizeToPowerOfTwo(const Image& image);

}  // namespace aperture
