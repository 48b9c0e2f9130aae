// The .apv file (seed 001, section 2.4): the packed texture with run lengths instead of end steps,
// each length a variable-length number of 7-bit groups, the 8th bit 1 on the last byte of a number
// and 0 when another byte follows. We add a magic number, a version and a CRC-32, and (version 2)
// compress the runs with zstd, which makes the files smaller than the optimised PNG of the same
// map (docs/BENCHMARKS.md, "Packed files against optimised PNG").
//
// Layout, version 2 (what EncodeApv writes), little-endian:
//   0   8  magic 89 'A' 'P' 'V' 0D 0A 1A 0A   (PNG-style: catches text-mode and 7-bit damage)
//   8   2  version = 2
//   10  1  curve: 0 Hilbert, 1 Morton
//   11  1  run coder: 1 zstd (the only one)
//   12  4  width            1..65536
//   16  4  height           1..65536
//   20  4  palette size     1..256
//   24  4  run count        1..width*height
//   28  8  run block bytes (compressed)
//   36  8  run block bytes once decompressed: 2..6 per run
//   44     palette: palette size x 4 bytes r, g, b, a
//   ..     run block: one zstd frame holding every run's length L_i = S_i - S_{i-1} (S_{-1} = -1;
//          steps outside a non-square texture are counted) as 7-bit groups, lowest group first,
//          then every run's palette index P_i (1 byte each). Lengths apart from indices compress
//          a fifth better than the two interleaved.
//   end 4  CRC-32 of every byte before it
//
// Version 1 (still read; written only on request): the same header up to byte 36 with the
// version 1 and byte 11 reserved (0), then the palette, then the run block uncompressed and
// interleaved: per run its length as above, then P_i.
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
inline constexpr uint16_t kApvVersionPlain = 1;  // runs interleaved, uncompressed
inline constexpr uint16_t kApvVersionZstd = 2;   // lengths, then indices, one zstd frame
inline constexpr uint16_t kApvVersion = kApvVersionZstd;
inline constexpr size_t kApvHeaderSize = 36;      // version 1
inline constexpr size_t kApvZstdHeaderSize = 44;  // version 2: the decompressed size follows
inline constexpr uint8_t kApvCoderZstd = 1;

struct ApvWriteOptions {
  uint16_t version = kApvVersion;  // kApvVersionPlain writes the older, uncompressed layout
  // Files are written once and read often: zstd's strong levels cost about a second on a dense
  // 8192 map and keep every map here below its optimised PNG.
  int zstd_level = 19;
};
std::vector<uint8_t> EncodeApv(const PackedTextureView& texture,
                               const ApvWriteOptions& options = {});

struct ApvReadOptions {
  bool verify_checksum = true;  // false lets a fuzzer reach the structural checks
};
// Every failure is an InvalidArgument (DataLoss for a checksum mismatch) naming the problem;
// never reads outside `bytes`. Version 1 never allocates more than the file can describe; a
// version 2 run block is decompressed in chunks and the runs are kept as they arrive, so memory
// grows only with runs the stream really holds.
absl::StatusOr<PackedTexture> DecodeApv(std::span<const uint8_t> bytes,
                                        const ApvReadOptions& options = {});

bool LooksLikeApv(std::span<const uint8_t> bytes);  // magic only

// The version field of an .apv file, 0 when the bytes are too short to hold one.
uint16_t ApvVersionOf(std::span<const uint8_t> bytes);

// What the decoded texture will take in memory, from the header alone (the run count it
// declares): a budget can weigh a compressed file before decoding it. At least bytes.size().
uint64_t ApvDecodedBytesEstimate(std::span<const uint8_t> bytes);

absl::StatusOr<std::vector<uint8_t>> ReadFileBytes(const std::string& path);
absl::Status WriteFileBytes(const std::string& path, std::span<const uint8_t> bytes);

absl::StatusOr<PackedTexture> ReadApvFile(const std::string& path);
absl::Status WriteApvFile(const std::string& path, const PackedTextureView& texture,
                          const ApvWriteOptions& options = {});

}  // namespace aperture::packed
