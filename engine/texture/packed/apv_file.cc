#include "texture/packed/apv_file.h"

#include <algorithm>
#include <cstring>
#include <fstream>
#include <iterator>

#include "absl/strings/str_cat.h"
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

std::vector<uint8_t> EncodeApv(const PackedTextureView& texture) {
  std::vector<uint8_t> out(std::begin(kApvMagic), std::end(kApvMagic));
  PutU16(out, kApvVersion);
  out.push_back(static_cast<uint8_t>(texture.curve()));
  out.push_back(0);
  PutU32(out, texture.width());
  PutU32(out, texture.height());
  PutU32(out, static_cast<uint32_t>(texture.palette().size()));
  PutU32(out, static_cast<uint32_t>(texture.run_count()));
  const size_t runs_size_at = out.size();
  PutU64(out, 0);
  for (uint32_t colour : texture.palette()) PutU32(out, colour);
  const size_t runs_begin = out.size();
  int64_t previous = -1;
  for (size_t i = 0; i < texture.run_count(); ++i) {
    PutRunLength(out, static_cast<uint64_t>(int64_t{texture.steps()[i]} - previous));
    out.push_back(texture.indices()[i]);
    previous = texture.steps()[i];
  }
  const uint64_t runs_size = out.size() - runs_begin;
  for (int i = 0; i < 8; ++i) out[runs_size_at + i] = static_cast<uint8_t>(runs_size >> (8 * i));
  PutU32(out, Crc32(out));
  return out;
}

bool LooksLikeApv(std::span<const uint8_t> bytes) {
  return bytes.size() >= sizeof(kApvMagic) &&
         std::equal(std::begin(kApvMagic), std::end(kApvMagic), bytes.begin());
}

absl::StatusOr<PackedTexture> DecodeApv(std::span<const uint8_t> bytes,
                                        const ApvReadOptions& options) {
  if (!LooksLikeApv(bytes)) return Bad("wrong magic number (not an .apv file)");
  if (bytes.size() < kApvHeaderSize + 4)
    return Bad(absl::StrCat("truncated: ", bytes.size(), " bytes, the header alone needs ",
                            kApvHeaderSize + 4));
  const uint8_t* p = bytes.data();
  const uint64_t version = GetLE(p + 8, 2);
  if (version != kApvVersion)
    return Bad(absl::StrCat("version ", version, ", this reader knows ", kApvVersion));
  const uint8_t curve = p[10];
  const uint64_t width = GetLE(p + 12, 4), height = GetLE(p + 16, 4);
  const uint64_t palette_size = GetLE(p + 20, 4), run_count = GetLE(p + 24, 4);
  const uint64_t runs_size = GetLE(p + 28, 8);
  if (palette_size == 0 || palette_size > kMaxPaletteSize)
    return Bad(absl::StrCat("palette size ", palette_size, " outside 1..256"));
  // Sizes before any allocation: the file must be exactly header + palette + runs + checksum.
  const uint64_t body = bytes.size() - kApvHeaderSize - 4;
  if (runs_size > body || palette_size * 4 != body - runs_size) {
    if (runs_size > body || palette_size * 4 > body - runs_size)
      return Bad(absl::StrCat("truncated: ", bytes.size(), " bytes, the header announces ",
                              kApvHeaderSize + palette_size * 4 + 4, " + ", runs_size));
    return Bad("trailing bytes after the run block");
  }
  if (options.verify_checksum) {
    const uint32_t stored = static_cast<uint32_t>(GetLE(p + bytes.size() - 4, 4));
    if (Crc32(bytes.first(bytes.size() - 4)) != stored)
      return absl::DataLossError(".apv: checksum mismatch (file corrupted)");
  }
  if (p[11] != 0) return Bad("reserved header byte is not 0");
  if (curve > static_cast<uint8_t>(Curve::kMorton))
    return Bad(absl::StrCat("unknown curve ", curve));
  if (width == 0 || height == 0 || width > kMaxTextureSide || height > kMaxTextureSide)
    return Bad(absl::StrCat("size ", width, "x", height, " outside 1..65536 per side"));
  if (run_count == 0 || run_count > width * height)
    return Bad(absl::StrCat("run count ", run_count, " outside 1..width*height"));
  if (run_count > runs_size / 2)
    return Bad(absl::StrCat("run count ", run_count, " needs at least ", run_count * 2,
                            " bytes, the run block has ", runs_size));

  std::vector<uint32_t> palette(palette_size);
  for (uint64_t i = 0; i < palette_size; ++i)
    palette[i] = static_cast<uint32_t>(GetLE(p + kApvHeaderSize + 4 * i, 4));
  const uint32_t last = LastStepInside(static_cast<Curve>(curve), static_cast<uint32_t>(width),
                                       static_cast<uint32_t>(height));
  std::vector<uint32_t> steps(run_count);
  std::vector<uint8_t> indices(run_count);
  const uint8_t* in = p + kApvHeaderSize + 4 * palette_size;
  const uint8_t* const end = in + runs_size;
  int64_t step = -1;
  for (uint64_t i = 0; i < run_count; ++i) {
    uint64_t length = 0;
    for (int shift = 0;; shift += 7) {
      if (in == end) return Bad(absl::StrCat("run block ends inside run ", i));
      if (shift > 28) return Bad(absl::StrCat("run ", i, ": length longer than 5 bytes"));
      const uint8_t b = *in++;
      length |= uint64_t{b & 0x7Fu} << shift;
      if (b & 0x80) break;
    }
    if (length == 0) return Bad(absl::StrCat("run ", i, " has length 0 (steps not increasing)"));
    step += static_cast<int64_t>(length);
    if (step > int64_t{last})
      return Bad(absl::StrCat("run ", i, " ends at step ", step, ", past the texture's last texel ",
                              last));
    if (in == end) return Bad(absl::StrCat("run block ends before the colour of run ", i));
    const uint8_t index = *in++;
    if (index >= palette_size)
      return Bad(
          absl::StrCat("run ", i, " has palette index ", index, ", palette has ", palette_size));
    steps[i] = static_cast<uint32_t>(step);
    indices[i] = index;
  }
  if (in != end) return Bad("run block has bytes after the last run");
  if (step != int64_t{last})
    return Bad(absl::StrCat("runs cover steps up to ", step, ", the texture needs ", last));
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

absl::Status WriteApvFile(const std::string& path, const PackedTextureView& texture) {
  return WriteFileBytes(path, EncodeApv(texture));
}

}  // namespace aperture::packed
