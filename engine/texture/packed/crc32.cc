#include "texture/packed/crc32.h"

#include <zlib.h>

#include <algorithm>

namespace aperture::packed {

uint32_t Crc32(std::span<const uint8_t> bytes, uint32_t crc) {
  // zlib's crc32 continues from an earlier result and takes at most a uInt of bytes at a time.
  uLong value = crc;
  for (size_t at = 0; at < bytes.size();) {
    const size_t n = std::min<size_t>(bytes.size() - at, 1u << 30);
    value = ::crc32(value, bytes.data() + at, static_cast<uInt>(n));
    at += n;
  }
  return static_cast<uint32_t>(value);
}

}  // namespace aperture::packed
