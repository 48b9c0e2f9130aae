#include "scene/encoded_texture.h"

#include <algorithm>

#include "absl/strings/str_cat.h"
#include "texture/image_file.h"
#include "texture/packed/apv_file.h"
#include "texture/prefiltered_table.h"

namespace aperture {

EncodedTextureInfo RasterTextureCost(uint32_t width, uint32_t height) {
  // Raster textures are resampled to powers of two per side (ResizeToPowerOfTwo), and their
  // tables to the square of the longer side (BuildPrefilteredTable).
  auto next = [](uint32_t n) {
    uint64_t p = 1;
    while (p < n) p *= 2;
    return p;
  };
  const uint64_t w = next(width), h = next(height);
  int log2_square = 0;
  while ((uint64_t{1} << log2_square) < std::max(w, h)) ++log2_square;
  EncodedTextureInfo info;
  info.width = width;
  info.height = height;
  info.texture_bytes = w * h * sizeof(Rgba) * 4 / 3;
  info.table_bytes = 4 * TableTexels(log2_square);  // 8-bit RGBA texels (kTexelRgba8)
  return info;
}

absl::StatusOr<EncodedTextureInfo> InspectEncodedTexture(std::span<const uint8_t> bytes) {
  if (packed::LooksLikeApv(bytes)) {
    auto texture = packed::DecodeApv(bytes);
    if (!texture.ok())
      return absl::InvalidArgumentError(
          absl::StrCat("packed texture (.apv): ", texture.status().message()));
    EncodedTextureInfo info;
    info.packed = true;
    info.width = texture->view().width();
    info.height = texture->view().height();
    info.texture_bytes = texture->bytes().size();
    return info;
  }
  auto header = ReadImageHeader(bytes);
  if (!header.ok()) return header.status();
  return RasterTextureCost(static_cast<uint32_t>(header->width),
                           static_cast<uint32_t>(header->height));
}

absl::StatusOr<EncodedTextureInfo> EstimateEncodedTexture(std::span<const uint8_t> bytes) {
  if (packed::LooksLikeApv(bytes)) {
    EncodedTextureInfo info;
    info.packed = true;
    info.texture_bytes = packed::ApvDecodedBytesEstimate(bytes);  // the runs decompressed
    return info;
  }
  return InspectEncodedTexture(bytes);
}

}  // namespace aperture
