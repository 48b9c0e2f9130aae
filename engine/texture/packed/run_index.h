// Faster texel access than the paper's binary search (seed 001, section 2.3, goes past it).
//
// Both curves visit every aligned 2^j x 2^j block as one contiguous range of steps, so a coarse
// grid of such blocks ("cells", row-major, indexed by the high bits of x and y) can hold for each
// cell the range of runs that cover it. A cell inside a single run (most cells of a map: big flat
// areas) is answered by the grid alone, without computing the curve step. A cell of several runs
// has a detail record (when such cells are few, as on maps): 4 x 4 subcells with their own run
// ranges, so most of its texels are answered without a search too, and where its block starts on
// the curve with the curve's orientation there, so the step of a texel is that start plus one
// lookup in a small table of the block's own curve instead of a descent over every level. What is
// left is a search over a short run range: one SIMD pass for up to 16 runs, else a branch-free
// lower bound. Batched lookups
// answer a batch in passes (cells, subcells, searches), the first two without a branch per texel.
// Built from a view in O(cells x log runs); derived data, not part of the packed format.
#pragma once

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include <cstdint>
#include <span>
#include <vector>

#include "texture/packed/packed_texture.h"

namespace aperture::packed {

class RunIndex {
 public:
  struct Options {
    // Cells of 2^cell_bits texels per side; -1 picks the smallest with at least three runs per
    // cell on average (a cell of several runs brings a 68-byte detail record, so cells are not
    // made as small as the runs). On the 8192 maps: cells of 32 x 32 texels, a 512 KiB grid.
    int cell_bits = -1;
    // Answer single-run cells from the grid alone. Always off at 2^24 runs or more, where a run
    // number no longer fits beside the palette index in 32 bits.
    bool single_run_shortcut = true;
    // Detail records for cells of several runs (cells of 4 x 4 to 64 x 64 texels, with the
    // shortcut): kAuto builds them when there is at most one such cell per 8 runs.
    enum class Details { kAuto, kAlways, kNever };
    Details details = Details::kAuto;
  };
  explicit RunIndex(const PackedTextureView& texture) : RunIndex(texture, Options{}) {}
  RunIndex(const PackedTextureView& texture, const Options& options);

  uint8_t PaletteIndexAt(uint32_t x, uint32_t y) const {
    const Cell& cell = CellOf(x, y);
    if (!shortcut_) return indices_[SearchRuns(cell.first, cell.last, StepOf(x, y))];
    // With the shortcut, `first` holds (run << 8) | palette index of that run.
    const uint32_t run = cell.first >> 8;
    if (run == cell.last) return static_cast<uint8_t>(cell.first);
    if (!(cell.last & kHasDetail)) return indices_[SearchRuns(run, cell.last, StepOf(x, y))];
    const uint32_t* detail = &details_[cell.last & ~kHasDetail];
    const uint32_t sub = detail[1 + SubcellOf(x, y)];
    const uint32_t lo = run + (sub >> 20), hi = run + ((sub >> 8) & 0xFFFu);
    if (lo == hi) return static_cast<uint8_t>(sub);
    return indices_[SearchRuns(lo, hi, LocalStep(detail[0], x, y))];
  }
  uint32_t ColorAt(uint32_t x, uint32_t y) const { return palette_[PaletteIndexAt(x, y)]; }

  // Index of the run holding texel (x, y) (same answer as the view's RunOfStep(StepOf(x, y))).
  size_t RunAt(uint32_t x, uint32_t y) const {
    const Cell& cell = CellOf(x, y);
    if (!shortcut_) return SearchRuns(cell.first, cell.last, StepOf(x, y));
    const uint32_t run = cell.first >> 8;
    if (run == cell.last) return run;
    if (!(cell.last & kHasDetail)) return SearchRuns(run, cell.last, StepOf(x, y));
    const uint32_t* detail = &details_[cell.last & ~kHasDetail];
    const uint32_t sub = detail[1 + SubcellOf(x, y)];
    return SearchRuns(run + (sub >> 20), run + ((sub >> 8) & 0xFFFu), LocalStep(detail[0], x, y));
  }

  // The runs [lo, hi] that cover the aligned block of 2^level texels a side with top-left texel
  // (x, y) hold all of the block's runs, when the grid knows such a range: the block lies within
  // one cell (or, for a cell with a detail record, within one subcell). False otherwise.
  bool RunsAround(uint32_t x, uint32_t y, int level, uint32_t& lo, uint32_t& hi) const {
    if (level > cell_bits_) return false;
    const Cell& cell = CellOf(x, y);
    if (!shortcut_) {
      if (cell.last & kHasDetail) return false;
      lo = cell.first, hi = cell.last;
      return true;
    }
    const uint32_t run = cell.first >> 8;
    if (!(cell.last & kHasDetail)) {
      lo = run, hi = cell.last;
      return true;
    }
    if (level > cell_bits_ - 2) return false;
    const uint32_t sub = details_[(cell.last & ~kHasDetail) + 1 + SubcellOf(x, y)];
    lo = run + (sub >> 20), hi = run + ((sub >> 8) & 0xFFFu);
    return true;
  }

  // colours[i] = ColorAt(xs[i], ys[i]); spans of equal length.
  void ColorsAt(std::span<const uint32_t> xs, std::span<const uint32_t> ys,
                std::span<uint32_t> colours) const;

  int cell_bits() const { return cell_bits_; }
  size_t byte_size() const {
    return cells_.size() * sizeof(Cell) + details_.size() * sizeof(uint32_t) +
           local_steps_.size() * sizeof(uint16_t);
  }

 private:
  struct Cell {
    uint32_t first;  // first run (shifted left by 8 beside its palette index with the shortcut)
    // Last run; or, for a cell of several runs with a detail record, kHasDetail | its offset.
    uint32_t last;
  };
  // Detail records: [0] the curve step of the block's start (a multiple of 4^cell_bits, so of 4)
  // | the orientation of the curve inside the block (the Hilbert sub-square state; 0 for Morton);
  // [1 + 4 sy + sx] subcell (sx, sy): (its first run - the cell's first) << 20 | (its last run -
  // the cell's first) << 8 | palette index of its first run. The offsets are below 4^cell_bits,
  // which fits 12 bits for cells of up to 64 x 64 texels; smaller cells than 4 x 4 have none.
  static constexpr uint32_t kHasDetail = 0x80000000u;
  static constexpr int kMinDetailBits = 2, kMaxDetailBits = 6;
  static constexpr size_t kDetailWords = 17;

  void AddDetail(const PackedTextureView& texture, Cell& cell, uint32_t x0, uint32_t y0,
                 uint64_t start, size_t first);
  // The first curve step of cell (cx, cy)'s block.
  uint64_t CellStart(size_t cx, size_t cy) const {
    const uint32_t corner =
        StepOf(static_cast<uint32_t>(cx << cell_bits_), static_cast<uint32_t>(cy << cell_bits_));
    return corner & ~((uint64_t{1} << (2 * cell_bits_)) - 1);
  }
  const Cell& CellOf(uint32_t x, uint32_t y) const {
    return cells_[size_t{y >> cell_bits_} * columns_ + (x >> cell_bits_)];
  }
  uint32_t SubcellOf(uint32_t x, uint32_t y) const {
    const int shift = cell_bits_ - 2;
    return (((y >> shift) & 3u) << 2) | ((x >> shift) & 3u);
  }
  uint32_t StepOf(uint32_t x, uint32_t y) const { return CurveStep(curve_, order_, x, y); }
  // The step of (x, y) inside a cell whose detail starts with `start_and_state`.
  uint32_t LocalStep(uint32_t start_and_state, uint32_t x, uint32_t y) const {
    const uint32_t mask = (1u << cell_bits_) - 1;
    return (start_and_state & ~3u) | local_steps_[((start_and_state & 3u) << (2 * cell_bits_)) |
                                                  ((y & mask) << cell_bits_) | (x & mask)];
  }
  // The first run in [lo, hi] whose end step is >= step; the answer is known to lie in [lo, hi].
  size_t SearchRuns(uint32_t lo, uint32_t hi, uint32_t step) const {
    const uint32_t n = hi - lo + 1;
    if (n <= kScanRuns && size_t{lo} + kScanRuns <= run_count_) return lo + CountBelow(lo, n, step);
    const uint32_t* base = steps_ + lo;
    size_t left = n;
    // Branch-free lower bound: the answer stays in [base, base + left).
    while (left > 1) {
      const size_t half = left / 2;
      base = (base[half - 1] < step) ? base + half : base;
      left -= half;
    }
    return static_cast<size_t>(base - steps_);
  }
  // How many of the n <= 16 end steps from run lo are below `step`: one pass over 16 entries
  // (readable: lo + 16 <= run count) with no dependent loads, instead of a halving search.
  static constexpr uint32_t kScanRuns = 16;
  uint32_t CountBelow(uint32_t lo, uint32_t n, uint32_t step) const {
#if defined(__SSE2__)
    // Unsigned compare as signed after flipping the top bit.
    const __m128i flip = _mm_set1_epi32(static_cast<int>(0x80000000u));
    const __m128i target = _mm_xor_si128(_mm_set1_epi32(static_cast<int>(step)), flip);
    uint32_t below = 0;
    for (int k = 0; k < 4; ++k) {
      const __m128i v = _mm_xor_si128(
          _mm_loadu_si128(reinterpret_cast<const __m128i*>(steps_ + lo + 4 * k)), flip);
      below |= static_cast<uint32_t>(_mm_movemask_ps(_mm_castsi128_ps(_mm_cmplt_epi32(v, target))))
               << (4 * k);
    }
    return static_cast<uint32_t>(__builtin_popcount(below & ((1u << n) - 1)));
#else
    uint32_t below = 0;
    for (uint32_t k = 0; k < n; ++k) below += steps_[lo + k] < step;
    return below;
#endif
  }

  Curve curve_;
  int order_;
  int cell_bits_ = 0;
  bool shortcut_ = true;
  size_t columns_ = 1;
  size_t run_count_;
  const uint32_t* steps_;
  const uint8_t* indices_;
  const uint32_t* palette_;
  std::vector<Cell> cells_;
  std::vector<uint32_t> details_;
  // [orientation][y][x] of a cell: the step inside the block (when cells have details).
  std::vector<uint16_t> local_steps_;
};

}  // namespace aperture::packed
