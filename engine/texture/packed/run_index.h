// Faster texel access than the paper's binary search (seed 001, section 2.3, goes past it).
//
// Both curves visit every aligned 2^j x 2^j block as one contiguous range of steps, so a coarse
// grid of such blocks ("cells", row-major, indexed by the high bits of x and y) can hold for each
// cell the range of runs that cover it. A cell inside a single run (most cells of a map: big flat
// areas) is answered by the grid alone, without computing the curve step; any other cell needs the
// step and a branch-free lower bound over its short run range. Batched lookups overlap the memory
// latency of several texels. Built from a view in O(cells x log runs); derived data, not part of
// the packed format.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "texture/packed/packed_texture.h"

namespace aperture::packed {

class RunIndex {
 public:
  struct Options {
    // Cells of 2^cell_bits texels per side; -1 picks the smallest with at most one cell per two
    // runs (on the 8192 maps: 32 x 32 cells, a 512 KiB grid).
    int cell_bits = -1;
    // Answer single-run cells from the grid alone. Always off at 2^24 runs or more, where a run
    // number no longer fits beside the palette index in 32 bits.
    bool single_run_shortcut = true;
  };
  explicit RunIndex(const PackedTextureView& texture) : RunIndex(texture, Options{}) {}
  RunIndex(const PackedTextureView& texture, const Options& options);

  uint8_t PaletteIndexAt(uint32_t x, uint32_t y) const {
    const Cell cell = cells_[size_t{y >> cell_bits_} * columns_ + (x >> cell_bits_)];
    if (!shortcut_) return indices_[SearchRuns(cell.first, cell.last, StepOf(x, y))];
    // With the shortcut, `first` holds (run << 8) | palette index of that run.
    if ((cell.first >> 8) == cell.last) return static_cast<uint8_t>(cell.first);
    return indices_[SearchRuns(cell.first >> 8, cell.last, StepOf(x, y))];
  }
  uint32_t ColorAt(uint32_t x, uint32_t y) const { return palette_[PaletteIndexAt(x, y)]; }

  // Index of the run holding texel (x, y) (same answer as the view's RunOfStep(StepOf(x, y))).
  size_t RunAt(uint32_t x, uint32_t y) const {
    const Cell cell = cells_[size_t{y >> cell_bits_} * columns_ + (x >> cell_bits_)];
    return SearchRuns(shortcut_ ? cell.first >> 8 : cell.first, cell.last, StepOf(x, y));
  }

  // colours[i] = ColorAt(xs[i], ys[i]); spans of equal length.
  void ColorsAt(std::span<const uint32_t> xs, std::span<const uint32_t> ys,
                std::span<uint32_t> colours) const;

  int cell_bits() const { return cell_bits_; }
  size_t byte_size() const { return cells_.size() * sizeof(Cell); }

 private:
  struct Cell {
    uint32_t first;  // first run (shifted left by 8 beside its palette index with the shortcut)
    uint32_t last;   // last run
  };

  uint32_t StepOf(uint32_t x, uint32_t y) const { return CurveStep(curve_, order_, x, y); }
  // The first run in [lo, hi] whose end step is >= step; the answer is known to lie in [lo, hi].
  size_t SearchRuns(uint32_t lo, uint32_t hi, uint32_t step) const {
    const uint32_t* base = steps_ + lo;
    size_t n = size_t{hi} - lo + 1;
    // Branch-free lower bound: the answer stays in [base, base + n).
    while (n > 1) {
      const size_t half = n / 2;
      base = (base[half - 1] < step) ? base + half : base;
      n -= half;
    }
    return static_cast<size_t>(base - steps_);
  }

  Curve curve_;
  int order_;
  int cell_bits_ = 0;
  bool shortcut_ = true;
  size_t columns_ = 1;
  const uint32_t* steps_;
  const uint8_t* indices_;
  const uint32_t* palette_;
  std::vector<Cell> cells_;
};

}  // namespace aperture::packed
