// CRC-32 (IEEE 802.3) of zlib, the .apv file checksum; `crc` continues an earlier result.
#pragma once

#include <cstdint>
#include <span>

namespace aperture::packed {

uint32_t Crc32(std::span<const uint8_t> bytes, uint32_t crc = 0);

}  // namespace aperture::packed
