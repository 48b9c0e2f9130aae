// libFuzzer target over uploads: any bytes are a texture (a raster image
// header within the limits, or a valid .apv) or a clear error; a small accepted raster image is
// then decoded as the scene build would, and must decode to the size its header declared.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <span>

#include "scene/encoded_texture.h"
#include "texture/image_file.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::span<const uint8_t> bytes(data, size);
  auto texture = aperture::InspectEncodedTexture(bytes);
  if (!texture.ok() || texture->packed) return 0;
  if (uint64_t{texture->width} * texture->height > 256 * 256) return 0;
  auto image = aperture::DecodeImage(bytes);
  if (image.ok() && (static_cast<uint32_t>(image->width()) != texture->width ||
                     static_cast<uint32_t>(image->height()) != texture->height))
    std::abort();
  return 0;
}
