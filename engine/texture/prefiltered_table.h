// The prefiltered anisotropic texture table of seed 000 (Kovalev & Tarasov): every box-filtered
// copy of a periodic 2^n x 2^n texture, for H, L powers of two and lambda = H / L tilts, stored
// as one flat, offset-only block (header, directory, texels) that can be written to a file or
// shared memory and used in place. This header describes the layout once; PrefilteredTable is a
// validated read-only view of such a block.
//
// Cells. Cell (j, i) holds the copies for L = 2^j (half-thickness, j = 0..n) and H = 2^(i+j)
// (half-extent along the major axis, i = 0..n-1): the paper's table for n = 6 read by columns.
// Resolution along the minor axis 2^(n-j); along the major axis 2^(n-i-j), never below
// min(2, minor) (the frozen region 2^(n-1) < H <= 2^(2n-1), where lambda stops growing and L is
// effectively raised). lambda = minor / major. One untilted copy when lambda = 1, else
// TiltsPerAxis(lambda) tilted to U (major axis U, short sides parallel to V) then as many tilted
// to V, in the order of TiltTangent. Seed 000's lambda copies cost 4^(n-j) texels a cell, so
// each diagonal i costs S_n = (4^(n+1) - 1) / 3 and the cells n * S_n (seed 000, memory
// estimate); the end tilts add four copies to every cell of lambda >= 4 (EndTiltTexels). One
// extra copy,
// the unfiltered texture (the "base", used for magnification), comes first.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "absl/status/statusor.h"

namespace aperture {

inline constexpr char kTableMagic[8] = {'A', 'P', 'T', 'A', 'B', 'L', 'E', '0'};
inline constexpr uint32_t kTableVersion = 3;  // 3: the end tilts (TiltsPerAxis)
inline constexpr uint32_t kTexelRgba8 = 1;    // 4 bytes per texel: linear RGBA, unorm 8-bit
inline constexpr int kTableMaxLog2Size = 13;  // 8192 x 8192: 5.6 GB

// Plain old data at offset 0. All offsets are bytes from the start of the block.
struct TableHeader {
  char magic[8];
  uint32_t version;
  uint32_t header_bytes;  // sizeof(TableHeader)
  uint32_t log2_size;     // n: the texture is 2^n x 2^n
  uint32_t texel_format;  // kTexelRgba8
  uint32_t copy_count;    // directory entries
  uint32_t build_milliseconds;
  uint64_t directory_offset;             // CopyEntry[copy_count]
  uint64_t data_offset;                  // first texel byte
  uint64_t total_bytes;                  // size of the whole block
  uint32_t source_width, source_height;  // the image before resampling to 2^n x 2^n
};
static_assert(sizeof(TableHeader) == 64);

enum class TiltAxis : uint8_t { kNone = 0, kU = 1, kV = 2 };
inline constexpr uint8_t kBaseCell = 0xff;  // log2_l / log2_ratio of the unfiltered base copy

struct CopyEntry {
  uint8_t log2_l;      // j (kBaseCell for the base copy)
  uint8_t log2_ratio;  // i = log2(H / L) (kBaseCell for the base copy)
  TiltAxis axis;
  uint8_t reserved;
  uint32_t tilt_index;     // k (TiltTangent)
  float tg;                // tangent of the long side to the major axis (0 when untilted)
  uint32_t lambda;         // the cell's lambda = height / width (tilt U) or width / height (tilt V)
  uint32_t width, height;  // texels along U and along V
  uint64_t offset;         // first texel, row-major (row 0 = v = 0)
};
static_assert(sizeof(CopyEntry) == 32);

// The table's shape, a pure function of n (used by the builder, the reader and the tests).
struct CellShape {
  uint32_t lambda;  // the resolution ratio minor / major (1: untilted)
  uint32_t major;   // resolution along the major axis (the axis of H)
  uint32_t minor;   // resolution along the minor axis (the axis of L)
};
CellShape TableCellShape(int n, int j, int i);
// seed 000: S_n = (4^(n+1) - 1) / 3 texels per diagonal, for the paper's lambda copies a cell.
uint64_t DiagonalTexels(int n);
// The texels of the end tilts (four copies a cell of lambda >= 4) over the whole table.
uint64_t EndTiltTexels(int n);
// The whole table: n * S_n + EndTiltTexels(n) + 4^n (the base copy).
uint64_t TableTexels(int n);

// The tilts of a cell, per axis. Seed 000 tilts a cell of resolution ratio lambda >= 2 by
// tg_k = (2k + 1) / (lambda / 2) - 1, k = 0 .. lambda / 2 - 1: the centres of lambda / 2 equal
// parts of [-1, 1]. Our extension adds the two ends, tg = -1 and +1, to every cell of
// lambda >= 4: without them a footprint whose long side is near a diagonal (|tg| near 1) reads
// a copy sheared by up to half a spacing to one side (3-4 dB lost within 8 degrees of the diagonals
// on the grass photo). Such a cell has lambda / 2
// + 2 tilts per axis, ascending: -1, the paper's, +1. A cell of lambda = 2 keeps the paper's one
// tilt, tg = 0 (its ends gained on the photos but lost 0.3-0.4 dB on the checkerboard's short
// footprints at a = 2, for 18 % more table).
uint32_t TiltsPerAxis(uint32_t lambda);  // 1 when lambda < 4 (untilted, or lambda = 2's tg = 0)
uint32_t CellCopies(uint32_t lambda);    // 1 when lambda < 2, else 2 TiltsPerAxis(lambda)
// tg of tilt k = 0 .. TiltsPerAxis(lambda) - 1 (0 when untilted).
float TiltTangent(uint32_t lambda, uint32_t k);

// A validated, read-only view of a table block. The block must outlive the view and be aligned
// to 8 bytes (malloc, mmap and shared memory are).
class PrefilteredTable {
 public:
  struct Cell {
    uint32_t first = 0;   // directory index of the cell's first copy
    uint32_t copies = 0;  // CellCopies of its lambda
  };

  // Checks magic, version, sizes, offsets and the directory against the shape of n.
  static absl::StatusOr<PrefilteredTable> View(std::span<const std::byte> block);

  int log2_size() const { return static_cast<int>(header().log2_size); }
  int size() const { return 1 << log2_size(); }
  const TableHeader& header() const { return *reinterpret_cast<const TableHeader*>(block_.data()); }
  std::span<const CopyEntry> directory() const { return directory_; }
  std::span<const std::byte> block() const { return block_; }

  const CopyEntry& base() const { return directory_[0]; }
  const Cell& cell(int j, int i) const { return cells_[j * log2_size() + i]; }
  const CopyEntry& copy(uint32_t index) const { return directory_[index]; }
  const uint8_t* texels(const CopyEntry& e) const {
    return reinterpret_cast<const uint8_t*>(block_.data()) + e.offset;
  }

 private:
  std::span<const std::byte> block_;
  std::span<const CopyEntry> directory_;
  std::vector<Cell> cells_;
};

// An owned table block (what the builder and the file reader return).
struct TableBlock {
  std::vector<std::byte> bytes;
  absl::StatusOr<PrefilteredTable> View() const { return PrefilteredTable::View(bytes); }
};

absl::Status WriteTableFile(const std::string& path, const TableBlock& block);
// Reads a whole file; NotFound if missing, FailedPrecondition if it is not a table (bad magic).
absl::StatusOr<TableBlock> ReadTableFile(const std::string& path);

}  // namespace aperture
