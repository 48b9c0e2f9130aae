// What an encoded texture (an upload, a scene's `encoded` source) is, read from its header (a
// raster image) or checked whole (a packed .apv, whose reader never allocates more than the file
// describes), before its pixels are decoded: the server refuses bytes
// that are no texture, and estimates what a scene will hold in memory before building it.
#pragma once

#include <cstdint>
#include <span>

#include "absl/status/statusor.h"

namespace aperture {

struct EncodedTextureInfo {
  bool packed = false;  // a seed 001 packed texture (.apv), sampled in place
  uint32_t width = 0, height = 0;
  // Bytes the scene holds once the texture is built, without seed 000's table: the float RGBA
  // mip-map of the power-of-two image (4/3 of its level 0), or the packed texture itself.
  uint64_t texture_bytes = 0;
  // Bytes of seed 000's table of the texture (a material filtered aniso); 0 for packed ones.
  uint64_t table_bytes = 0;
};

// InvalidArgument naming the problem for bytes that are no texture the engine takes.
absl::StatusOr<EncodedTextureInfo> InspectEncodedTexture(std::span<const uint8_t> bytes);

// The same figures for a raster of `width` x `height` texels (a decoded image, a checkerboard).
EncodedTextureInfo RasterTextureCost(uint32_t width, uint32_t height);

// The figures alone, as cheaply as they can be had: a raster image's header, or a packed
// texture's own size (it is held about as encoded); for estimates, not for validation.
absl::StatusOr<EncodedTextureInfo> EstimateEncodedTexture(std::span<const uint8_t> bytes);

}  // namespace aperture
