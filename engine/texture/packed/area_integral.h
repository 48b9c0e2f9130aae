// Exact area integrals over a packed texture, without unpacking (goes past seed 001, whose named
// gap is anti-aliasing). Both curves visit every aligned 2^j x 2^j block as one contiguous range of
// steps, so with prefix sums of colour per run the sum over a block costs two run searches, and an
// axis-aligned rectangle decomposes into O(perimeter in blocks) aligned blocks. The descent starts
// at the smallest aligned block holding the rectangle and carries each block's run range, found
// inside its parent's, so a block within a single run is constant (colour x overlap area,
// fractional edges included) and a block wholly inside the rectangle costs two prefix-sum lookups.
// Whole-texel sums are exact integers (uint64); only coverage weights of edge texels are doubles.
//
// Coordinates are texel units: texel (i, j) covers [i, i+1) x [j, j+1) (DESIGN.md). Rectangles
// may have fractional edges (edge texels weighted by coverage), extend past the texture and wrap
// (the texture repeats periodically), or span many periods.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "texture/packed/packed_texture.h"
#include "texture/packed/run_index.h"

namespace aperture::packed {

// Sums of the 8-bit channel values r, g, b, a (colour x area), and the area.
struct AreaSum {
  std::array<double, 4> channels{};
  double area = 0;
};

class AreaIntegrator {
 public:
  // The view's bytes must outlive the integrator. Prefix sums: 32 bytes per run.
  explicit AreaIntegrator(const PackedTextureView& texture);
  // With the texture's run index (which must outlive the integrator), a descent's first block
  // finds its runs inside its cell's range rather than over every run: the same runs, fewer
  // cache-missing steps of the search.
  AreaIntegrator(const PackedTextureView& texture, const RunIndex* index)
      : AreaIntegrator(texture) {
    index_ = index;
  }

  // Exact integer sums over texels [x0, x1) x [y0, y1) inside the texture (0 <= x0 <= x1 <= width,
  // likewise y).
  std::array<uint64_t, 4> SumTexels(uint32_t x0, uint32_t y0, uint32_t x1, uint32_t y1) const;

  // Integral of the periodic texture over [x0, x1) x [y0, y1) in texel units, x0 <= x1, y0 <= y1.
  AreaSum Integrate(double x0, double y0, double x1, double y1) const;

  // Integer sums over the steps first..last, all inside the texture.
  std::array<uint64_t, 4> SumSteps(uint32_t first, uint32_t last) const;
  // The same when the runs holding `first` and `last` are known: prefix sums only.
  std::array<uint64_t, 4> SumStepsInRuns(uint32_t first, uint32_t last, size_t first_run,
                                         size_t last_run) const;

 private:
  // An aligned block of the curve's square during a descent, with the runs that cover it.
  struct Block {
    int level;
    uint32_t x, y;          // top-left texel
    uint32_t state;         // Hilbert orientation
    uint64_t step0;         // first step
    size_t run_lo, run_hi;  // runs holding the block's first and last texture steps
  };
  // The four sub-blocks in curve order; the run range of each found inside the parent's.
  void Children(const Block& b, Block out[4]) const;
  // Sub-block `digit` in curve order, without its runs; FindRuns finds them inside the parent's.
  Block Child(const Block& b, uint32_t digit) const;
  void FindRuns(const Block& parent, Block& child) const;
  void FindRunsBySearch(const Block& parent, Block& child) const;
  struct BlockCache;
  size_t RunIn(size_t lo, size_t hi, uint64_t step) const;
  // The smallest aligned block holding texels [x0, x1] x [y0, y1] (inclusive, inside the
  // texture): the descent starts there, skipping the levels above it.
  Block Enclosing(uint32_t x0, uint32_t y0, uint32_t x1, uint32_t y1) const;
  // A block's runs by search (Enclosing's, when its thread has not just found them).
  void SetRuns(Block& b) const;
  std::array<uint64_t, 4> SumBlock(const Block& b, uint32_t x0, uint32_t y0, uint32_t x1,
                                   uint32_t y1) const;
  // Rectangle with fractional edges inside [0, width] x [0, height], in one descent: blocks
  // wholly inside by prefix sums, single-run blocks by colour x overlap area.
  void IntegrateBlock(const Block& b, double x0, double y0, double x1, double y1,
                      std::array<double, 4>& sum) const;

  // A rectangle inside the texture that reaches at most kMaxCells cells of the run index: each
  // cell (or, in a cell with a detail record, each subcell) inside a single run adds its colour x
  // overlap area from the index alone, and only the others are descended into, each from the
  // smallest block holding its part. Most footprints lie over cells of one colour each (of the
  // airport's at 1280x720, 81 % lie over at most 2 x 2 such cells). False (`sum` untouched) for a
  // larger rectangle.
  static constexpr uint32_t kMaxCells = 16;
  bool IntegrateOverCells(double x0, double y0, double x1, double y1,
                          std::array<double, 4>& sum) const;
  // The part of a rectangle over each aligned block of 2^level texels a side (the index's cells or
  // subcells) it reaches.
  void IntegrateOverBlocks(int level, double x0, double y0, double x1, double y1,
                           std::array<double, 4>& sum) const;
  // A rectangle inside the texture, descended into from the smallest block holding it.
  void IntegrateByDescent(double x0, double y0, double x1, double y1,
                          std::array<double, 4>& sum) const;
  // Adds run `run`'s colour x `area` to `sum`.
  void AddRunColour(size_t run, double area, std::array<double, 4>& sum) const;

  PackedTextureView texture_;
  const RunIndex* index_ = nullptr;
  // prefix_[i] = sum over runs < i of length x colour (length in steps; used only for runs wholly
  // inside a range of texture texels, where length = texel count).
  std::vector<std::array<uint64_t, 4>> prefix_;
  std::array<uint64_t, 4> total_{};
  uint64_t id_ = 0;  // this integrator's tag in the threads' caches of blocks (BlockCache)
};

}  // namespace aperture::packed
