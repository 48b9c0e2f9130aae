#include "texture/prefiltered_table.h"

#include <algorithm>
#include <cstring>
#include <fstream>

#include "absl/strings/str_cat.h"

namespace aperture {

CellShape TableCellShape(int n, int j, int i) {
  // seed 000, table for n = 6: minor resolution 2^n / L, major 2^n / H, the major resolution
  // frozen at 2 (or at the minor one when that is 1) for H > 2^(n-1).
  const uint32_t minor = 1u << (n - j);
  const int major_log2 = n - i - j;
  const uint32_t floor_major = std::min<uint32_t>(2, minor);
  const uint32_t major =
      major_log2 >= 1 ? std::max<uint32_t>(1u << major_log2, floor_major) : floor_major;
  return {minor / major, major, minor};
}

uint64_t DiagonalTexels(int n) { return ((uint64_t{1} << (2 * (n + 1))) - 1) / 3; }

uint64_t EndTiltTexels(int n) {
  uint64_t texels = 0;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i < n; ++i) {
      const CellShape s = TableCellShape(n, j, i);
      if (s.lambda >= 4) texels += 4 * uint64_t{s.major} * s.minor;
    }
  return texels;
}

uint64_t TableTexels(int n) {
  return static_cast<uint64_t>(n) * DiagonalTexels(n) + EndTiltTexels(n) + (uint64_t{1} << (2 * n));
}

uint32_t TiltsPerAxis(uint32_t lambda) { return lambda < 4 ? 1 : lambda / 2 + 2; }

uint32_t CellCopies(uint32_t lambda) { return lambda < 2 ? 1 : 2 * TiltsPerAxis(lambda); }

float TiltTangent(uint32_t lambda, uint32_t k) {
  if (lambda < 4) return 0.0f;  // untilted, or seed 000's one tilt of lambda = 2
  const uint32_t half = lambda / 2;
  if (k == 0) return -1.0f;
  if (k > half) return 1.0f;
  // seed 000's tilt k - 1.
  return static_cast<float>((2.0 * (k - 1) + 1.0) / half - 1.0);
}

absl::StatusOr<PrefilteredTable> PrefilteredTable::View(std::span<const std::byte> block) {
  auto bad = [](const std::string& why) {
    return absl::InvalidArgumentError(absl::StrCat("prefiltered table: ", why));
  };
  if (block.size() < sizeof(TableHeader) ||
      std::memcmp(block.data(), kTableMagic, sizeof(kTableMagic)) != 0)
    return absl::FailedPreconditionError("not a prefiltered table (bad magic)");
  if (reinterpret_cast<uintptr_t>(block.data()) % 8 != 0) return bad("block is not 8-byte aligned");
  TableHeader h;
  std::memcpy(&h, block.data(), sizeof(h));
  if (h.version != kTableVersion)
    return bad(absl::StrCat("version ", h.version, ", this reader knows ", kTableVersion));
  if (h.header_bytes != sizeof(TableHeader)) return bad("header size mismatch");
  if (h.texel_format != kTexelRgba8) return bad("unknown texel format");
  if (h.log2_size < 1 || h.log2_size > kTableMaxLog2Size) return bad("size out of range");
  if (h.total_bytes != block.size())
    return bad(absl::StrCat("block holds ", block.size(), " bytes, header says ", h.total_bytes));
  const int n = static_cast<int>(h.log2_size);
  if (h.directory_offset % 8 != 0 || h.directory_offset < sizeof(TableHeader) ||
      h.directory_offset + uint64_t{h.copy_count} * sizeof(CopyEntry) > h.data_offset ||
      h.data_offset > h.total_bytes)
    return bad("directory out of bounds");

  PrefilteredTable table;
  table.block_ = block;
  table.directory_ = {reinterpret_cast<const CopyEntry*>(block.data() + h.directory_offset),
                      h.copy_count};
  // Walk the expected shape and check every directory entry against it.
  uint32_t index = 0;
  auto check = [&](const CopyEntry& e, uint32_t w, uint32_t ht) -> absl::Status {
    if (e.width != w || e.height != ht) return bad(absl::StrCat("copy ", index, " has wrong size"));
    if (e.offset < h.data_offset || e.offset + uint64_t{w} * ht * 4 > h.total_bytes)
      return bad(absl::StrCat("copy ", index, " out of bounds"));
    // The samplers address a texel by its 32-bit index from the base's first texel.
    const uint64_t base = index == 0 ? e.offset : table.directory_[0].offset;
    if (e.offset < base || (e.offset - base) % 4 != 0 ||
        (e.offset - base) / 4 + uint64_t{w} * ht > (uint64_t{1} << 31))
      return bad(absl::StrCat("copy ", index, " is not at a 32-bit texel index of the base's"));
    return absl::OkStatus();
  };
  if (h.copy_count == 0) return bad("empty directory");
  {
    const CopyEntry& e = table.directory_[0];
    if (e.log2_l != kBaseCell) return bad("first copy is not the base");
    if (auto s = check(e, 1u << n, 1u << n); !s.ok()) return s;
    ++index;
  }
  table.cells_.resize(static_cast<size_t>(n + 1) * n);
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i < n; ++i) {
      const CellShape shape = TableCellShape(n, j, i);
      const uint32_t copies = CellCopies(shape.lambda);
      table.cells_[j * n + i] = {index, copies};
      for (uint32_t c = 0; c < copies; ++c, ++index) {
        if (index >= h.copy_count) return bad("directory too short");
        const CopyEntry& e = table.directory_[index];
        if (e.log2_l != j || e.log2_ratio != i || e.lambda != shape.lambda)
          return bad(absl::StrCat("copy ", index, " is not of cell (", j, ", ", i, ")"));
        const bool tilt_u = shape.lambda == 1 || c < copies / 2;
        const uint32_t w = tilt_u ? shape.major : shape.minor;
        const uint32_t ht = tilt_u ? shape.minor : shape.major;
        if (auto s = check(e, w, ht); !s.ok()) return s;
      }
    }
  }
  if (index != h.copy_count) return bad("directory too long");
  return table;
}

absl::Status WriteTableFile(const std::string& path, const TableBlock& block) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out) return absl::PermissionDeniedError(absl::StrCat("cannot create '", path, "'"));
  out.write(reinterpret_cast<const char*>(block.bytes.data()),
            static_cast<std::streamsize>(block.bytes.size()));
  out.close();
  if (!out) return absl::DataLossError(absl::StrCat("cannot write '", path, "'"));
  return absl::OkStatus();
}

absl::StatusOr<TableBlock> ReadTableFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) return absl::NotFoundError(absl::StrCat("cannot open '", path, "'"));
  const std::streamsize size = in.tellg();
  in.seekg(0);
  char magic[sizeof(kTableMagic)] = {};
  if (size < static_cast<std::streamsize>(sizeof(TableHeader)) || !in.read(magic, sizeof(magic)) ||
      std::memcmp(magic, kTableMagic, sizeof(magic)) != 0)
    return absl::FailedPreconditionError(absl::StrCat("'", path, "' is not a prefiltered table"));
  in.seekg(0);
  TableBlock block;
  block.bytes.resize(static_cast<size_t>(size));
  if (!in.read(reinterpret_cast<char*>(block.bytes.data()), size))
    return absl::DataLossError(absl::StrCat("cannot read '", path, "'"));
  return block;
}

}  // namespace aperture
