#include "texture/packed/apv_file.h"

#include <algorithm>
#include <cstring>
#include <fstream>
#include <iterator>

#include "absl/strings/str_cat.h"
#include "texture/packed/apv_run_stream.h"
#include "texture/packed/crc32.h"

namespace aperture::packed {
namespace {

void PutU16(std::vector<uint8_t>& out, uint16_t v) {
  for (int i = 0; i < 2; ++i) out.push_back(static_cast<uint8_t>(v >> (8 * i)));
}
void PutU32(std::vector<uint8_t>& out, uint32_t v) {
  for (int i = 0; i < 4; ++i) out.push_back(static_cast<uint8_t>(v >> (8 * i)));
}
void PutU64(std::vector<uint8_t>& out, uint64_t v) {
  for (int i = 0; i < 8; ++i) out.push_back(static_cast<uint8_t>(v >> (8 * i)));
}
uint64_t GetLE(const uint8_t* p, int bytes) {
  uint64_t v = 0;
  for (int i = bytes - 1; i >= 0; --i) v = (v << 8) | p[i];
  return v;
}

// seed 001, section 2.4: 7 significant bits per byte; the 8th bit is 1 on the last byte.
void PutRunLength(std::vector<uint8_t>& out, uint64_t v) {
  while (v >= 0x80) {
    out.push_back(static_cast<uint8_t>(v & 0x7F));
    v >>= 7;
  }
  out.push_back(static_cast<uint8_t>(v | 0x80));
}

absl::Status Bad(const std::string& what) {
  return absl::InvalidArgumentError(absl::StrCat(".apv: ", what));
}

}  // namespace

std::vector<uint8_t> EncodeApv(const PackedTextureView& texture, const ApvWriteOptions& options) {
  const bool zstd = options.version != kApvVersionPlain;
  std::vector<uint8_t> out(std::begin(kApvMagic), std::end(kApvMagic));
  PutU16(out, zstd ? kApvVersionZstd : kApvVersionPlain);
  out.push_back(static_cast<uint8_t>(texture.curve()));
  out.push_back(zstd ? kApvCoderZstd : 0);
  PutU32(out, texture.width());
  PutU32(out, texture.height());
  PutU32(out, static_cast<uint32_t>(texture.palette().size()));
  PutU32(out, static_cast<uint32_t>(texture.run_count()));
  std::vector<uint8_t> runs;
  runs.reserve(3 * texture.run_count());
  int64_t previous = -1;
  for (size_t i = 0; i < texture.run_count(); ++i) {
    PutRunLength(runs, static_cast<uint64_t>(int64_t{texture.steps()[i]} - previous));
    if (!zstd) runs.push_back(texture.indices()[i]);
    previous = texture.steps()[i];
  }
  if (zstd) {
    runs.insert(runs.end(), texture.indices().begin(), texture.indices().end());
    const uint64_t decoded_size = runs.size();
    runs = ZstdCompressFrame(runs, options.zstd_level);
    PutU64(out, runs.size());
    PutU64(out, decoded_size);
  } else {
    PutU64(out, runs.size());
  }
  for (uint32_t colour : texture.palette()) PutU32(out, colour);
  out.insert(out.end(), runs.begin(), runs.end());
  PutU32(out, Crc32(out));
  return out;
}

bool LooksLikeApv(std::span<const uint8_t> bytes) {
  return bytes.size() >= sizeof(kApvMagic) &&
         std::equal(std::begin(kApvMagic), std::end(kApvMagic), bytes.begin());
}

uint16_t ApvVersionOf(std::span<const uint8_t> bytes) {
  return bytes.size() < 10 ? 0 : static_cast<uint16_t>(GetLE(bytes.data() + 8, 2));
}

uint64_t ApvDecodedBytesEstimate(std::span<const uint8_t> bytes) {
  if (!LooksLikeApv(bytes) || bytes.size() < kApvHeaderSize) return bytes.size();
  const uint64_t palette_size = std::min<uint64_t>(GetLE(bytes.data() + 20, 4), kMaxPaletteSize);
  const uint64_t run_count = GetLE(bytes.data() + 24, 4);
  // PackedHeader, palette, 4-byte steps and 1-byte indices, alignment.
  return std::max<uint64_t>(bytes.size(),
                            sizeof(PackedHeader) + 4 * palette_size + 5 * run_count + 8);
}

namespace {

// One run length as 7-bit groups from `next` (a callable giving the next byte, false at the end).
template <typename Next>
absl::Status ReadRunLength(Next& next, uint64_t run, uint64_t& length) {
  length = 0;
  for (int shift = 0;; shift += 7) {
    uint8_t b;
    if (!next(b)) return Bad(absl::StrCat("run block ends inside run ", run));
    if (shift > 28) return Bad(absl::StrCat("run ", run, ": length longer than 5 bytes"));
    length |= uint64_t{b & 0x7Fu} << shift;
    if (b & 0x80) break;
  }
  if (length == 0) return Bad(absl::StrCat("run ", run, " has length 0 (steps not increasing)"));
  return absl::OkStatus();
}

struct RunLimits {
  uint64_t run_count;
  uint64_t palette_size;
  uint32_t last;  // the texture's last step
};

absl::Status AddStep(const RunLimits& limits, uint64_t run, uint64_t length, int64_t& step,
                     std::vector<uint32_t>& steps) {
  step += static_cast<int64_t>(length);
  if (step > int64_t{limits.last})
    return Bad(absl::StrCat("run ", run, " ends at step ", step, ", past the texture's last texel ",
                            limits.last));
  steps.push_back(static_cast<uint32_t>(step));
  return absl::OkStatus();
}

absl::Status CheckIndex(const RunLimits& limits, uint64_t run, uint8_t index) {
  if (index >= limits.palette_size)
    return Bad(absl::StrCat("run ", run, " has palette index ", index, ", palette has ",
                            limits.palette_size));
  return absl::OkStatus();
}

// Version 1: per run its length, then its index, straight from the file.
absl::Status ReadPlainRuns(std::span<const uint8_t> block, const RunLimits& limits,
                           std::vector<uint32_t>& steps, std::vector<uint8_t>& indices) {
  size_t at = 0;
  auto next = [&](uint8_t& b) {
    if (at == block.size()) return false;
    b = block[at++];
    return true;
  };
  int64_t step = -1;
  for (uint64_t i = 0; i < limits.run_count; ++i) {
    uint64_t length;
    if (absl::Status s = ReadRunLength(next, i, length); !s.ok()) return s;
    if (absl::Status s = AddStep(limits, i, length, step, steps); !s.ok()) return s;
    uint8_t index;
    if (!next(index)) return Bad(absl::StrCat("run block ends before the colour of run ", i));
    if (absl::Status s = CheckIndex(limits, i, index); !s.ok()) return s;
    indices.push_back(index);
  }
  if (at != block.size()) return Bad("run block has bytes after the last run");
  return absl::OkStatus();
}

// Version 2: every length, then every index, from one zstd frame. A failure the decompressor saw
// (corrupt, truncated, longer than declared) is reported rather than the parse error it caused.
absl::Status ReadZstdRuns(std::span<const uint8_t> block, uint64_t decoded_size,
                          const RunLimits& limits, std::vector<uint32_t>& steps,
                          std::vector<uint8_t>& indices) {
  ZstdFrameReader reader(block, decoded_size);
  auto next = [&](uint8_t& b) { return reader.Next(b); };
  auto first_cause = [&](absl::Status parse) {
    return reader.status().ok() ? parse : reader.status();
  };
  int64_t step = -1;
  for (uint64_t i = 0; i < limits.run_count; ++i) {
    uint64_t length;
    if (absl::Status s = ReadRunLength(next, i, length); !s.ok()) return first_cause(s);
    if (absl::Status s = AddStep(limits, i, length, step, steps); !s.ok()) return s;
  }
  for (uint64_t i = 0; i < limits.run_count; ++i) {
    uint8_t index;
    if (!next(index))
      return first_cause(Bad(absl::StrCat("run block ends before the colour of run ", i)));
    if (absl::Status s = CheckIndex(limits, i, index); !s.ok()) return s;
    indices.push_back(index);
  }
  return reader.Finish();
}

}  // namespace

absl::StatusOr<PackedTexture> DecodeApv(std::span<const uint8_t> bytes,
                                        const ApvReadOptions& options) {
  if (!LooksLikeApv(bytes)) return Bad("wrong magic number (not an .apv file)");
  if (bytes.size() < kApvHeaderSize + 4)
    return Bad(absl::StrCat("truncated: ", bytes.size(), " bytes, the header alone needs ",
                            kApvHeaderSize + 4));
  const uint8_t* p = bytes.data();
  const uint64_t version = GetLE(p + 8, 2);
  if (version != kApvVersionPlain && version != kApvVersionZstd)
    return Bad(absl::StrCat("version ", version, ", this reader knows ", kApvVersionPlain, " and ",
                            kApvVersionZstd));
  const bool zstd = version == kApvVersionZstd;
  const size_t header_size = zstd ? kApvZstdHeaderSize : kApvHeaderSize;
  if (bytes.size() < header_size + 4)
    return Bad(absl::StrCat("truncated: ", bytes.size(), " bytes, the version ", version,
                            " header alone needs ", header_size + 4));
  const uint8_t curve = p[10];
  const uint64_t width = GetLE(p + 12, 4), height = GetLE(p + 16, 4);
  const uint64_t palette_size = GetLE(p + 20, 4), run_count = GetLE(p + 24, 4);
  const uint64_t runs_size = GetLE(p + 28, 8);
  const uint64_t decoded_size = zstd ? GetLE(p + 36, 8) : runs_size;
  if (palette_size == 0 || palette_size > kMaxPaletteSize)
    return Bad(absl::StrCat("palette size ", palette_size, " outside 1..256"));
  // Sizes before any allocation: the file must be exactly header + palette + runs + checksum.
  const uint64_t body = bytes.size() - header_size - 4;
  if (runs_size > body || palette_size * 4 != body - runs_size) {
    if (runs_size > body || palette_size * 4 > body - runs_size)
      return Bad(absl::StrCat("truncated: ", bytes.size(), " bytes, the header announces ",
                              header_size + palette_size * 4 + 4, " + ", runs_size));
    return Bad("trailing bytes after the run block");
  }
  if (options.verify_checksum) {
    const uint32_t stored = static_cast<uint32_t>(GetLE(p + bytes.size() - 4, 4));
    if (Crc32(bytes.first(bytes.size() - 4)) != stored)
      return absl::DataLossError(".apv: checksum mismatch (file corrupted)");
  }
  if (zstd && p[11] != kApvCoderZstd)
    return Bad(absl::StrCat("unknown run coder ", p[11], " (1 is zstd)"));
  if (!zstd && p[11] != 0) return Bad("reserved header byte is not 0");
  if (curve > static_cast<uint8_t>(Curve::kMorton))
    return Bad(absl::StrCat("unknown curve ", curve));
  if (width == 0 || height == 0 || width > kMaxTextureSide || height > kMaxTextureSide)
    return Bad(absl::StrCat("size ", width, "x", height, " outside 1..65536 per side"));
  if (run_count == 0 || run_count > width * height)
    return Bad(absl::StrCat("run count ", run_count, " outside 1..width*height"));
  if (run_count > decoded_size / 2)
    return Bad(absl::StrCat("run count ", run_count, " needs at least ", run_count * 2,
                            " bytes, the run block has ", decoded_size));
  if (zstd && decoded_size > run_count * 6)
    return Bad(absl::StrCat("decompressed run block of ", decoded_size, " bytes, more than the ",
                            run_count * 6, " that ", run_count, " runs can take"));

  std::vector<uint32_t> palette(palette_size);
  for (uint64_t i = 0; i < palette_size; ++i)
    palette[i] = static_cast<uint32_t>(GetLE(p + header_size + 4 * i, 4));
  const RunLimits limits{run_count, palette_size,
                         LastStepInside(static_cast<Curve>(curve), static_cast<uint32_t>(width),
                                        static_cast<uint32_t>(height))};
  const std::span<const uint8_t> block = bytes.subspan(header_size + 4 * palette_size, runs_size);
  std::vector<uint32_t> steps;
  std::vector<uint8_t> indices;
  // A compressed block may claim more runs than it holds: reserve no more than a plain block of
  // its size could describe, and let the vectors grow with the runs that arrive.
  const uint64_t reserve = std::min<uint64_t>(run_count, std::max<uint64_t>(runs_size, 1 << 16));
  steps.reserve(reserve);
  indices.reserve(reserve);
  const absl::Status runs = zstd ? ReadZstdRuns(block, decoded_size, limits, steps, indices)
                                 : ReadPlainRuns(block, limits, steps, indices);
  if (!runs.ok()) return runs;
  if (steps.back() != limits.last)
    return Bad(
        absl::StrCat("runs cover steps up to ", steps.back(), ", the texture needs ", limits.last));
  return PackedTexture::Assemble(static_cast<uint32_t>(width), static_cast<uint32_t>(height),
                                 static_cast<Curve>(curve), palette, steps, indices);
}

absl::StatusOr<std::vector<uint8_t>> ReadFileBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return absl::NotFoundError(absl::StrCat("cannot open '", path, "'"));
  std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)),
                             std::istreambuf_iterator<char>());
  if (in.bad()) return absl::DataLossError(absl::StrCat("error reading '", path, "'"));
  return bytes;
}

absl::Status WriteFileBytes(const std::string& path, std::span<const uint8_t> bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out) return absl::PermissionDeniedError(absl::StrCat("cannot create '", path, "'"));
  out.write(reinterpret_cast<const char*>(bytes.data()),
            static_cast<std::streamsize>(bytes.size()));
  out.close();
  if (!out) return absl::DataLossError(absl::StrCat("error writing '", path, "'"));
  return absl::OkStatus();
}

absl::StatusOr<PackedTexture> ReadApvFile(const std::string& path) {
  auto bytes = ReadFileBytes(path);
  if (!bytes.ok()) return bytes.status();
  auto texture = DecodeApv(*bytes);
  if (!texture.ok())
    return absl::Status(texture.status().code(),
                        absl::StrCat("'", path, "': ", texture.status().message()));
  return texture;
}

absl::Status WriteApvFile(const std::string& path, const PackedTextureView& texture,
                          const ApvWriteOptions& options) {
  return WriteFileBytes(path, EncodeApv(texture, options));
}

}  // namespace aperture::packed
