// CRC-32 (IEEE 802.3, as zlib and PNG compute it), the .apv file checksum.
#pragma once

#include <cstdint>
#include <span>

namespace aperture::packed {

uint32_t Crc32(std::span<const uint8_t> bytes, uint32_t crc = 0);

}  // namespace aperture::packed
