// The .apv file (seed 001, section 2.4): the packed texture with run lengths instead of end steps,
// each length a variable-length number of 7-bit groups, the 8th bit 1 on the last byte of a number
// and 0 when another byte follows. We add a magic number, a version and a CRC-32.
//
// Layout, version 1, little-endian:
//   0   8  magic 89 'A' 'P' 'V' 0D 0A 1A 0A   (PNG-style: catches text-mode and 7-bit damage)
//   8   2  version = 1
//   10  1  curve: 0 Hilbert, 1 Morton
//   11  1  reserved, 0
//   12  4  width            1..65536
//   16  4  height           1..65536
//   20  4  palette size     1..256
//   24  4  run count        1..width*height
//   28  8  run block bytes
//   36     palette: palette size x 4 bytes r, g, b, a
//   ..     run block: per run the length L_i = S_i - S_{i-1} (S_{-1} = -1; steps outside a
//          non-square texture are counted) as 7-bit groups, lowest group first, then P_i (1 byte)
//   end 4  CRC-32 of every byte before it
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "texture/packed/packed_texture.h"

namespace aperture::packed {

inline constexpr uint8_t kApvMagic[8] = {0x89, 'A', 'P', 'V', 0x0D, 0x0A, 0x1A, 0x0A};
inline constexpr uint16_t kApvVersion = 1;
inline constexpr size_t kApvHeaderSize = 36;

std::vector<uint8_t> EncodeApv(const PackedTextureView& texture);

struct ApvReadOptions {
  bool verify_checksum = true;  // false lets a fuzzer reach the structural checks
};
// Every failure is an InvalidArgument (DataLoss for a checksum mismatch) naming the problem;
// never reads outside `bytes`, never allocates more than the file can describe.
absl::StatusOr<PackedTexture> DecodeApv(std::span<const uint8_t> bytes,
                                        const ApvReadOptions& options = {});

bool LooksLikeApv(std::span<const uint8_t> bytes);  // magic only

absl::StatusOr<std::vector<uint8_t>> ReadFileBytes(const std::string& path);
absl::Status WriteFileBytes(const std::string& path, std::span<const uint8_t> bytes);

absl::StatusOr<PackedTexture> ReadApvFile(const std::string& path);
absl::Status WriteApvFile(const std::string& path, const PackedTextureView& texture);

}  // namespace aperture::packed
