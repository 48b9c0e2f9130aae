#include "texture/packed/run_index.h"

#include <algorithm>

namespace aperture::packed {

RunIndex::RunIndex(const PackedTextureView& texture, const Options& options)
    : curve_(texture.curve()),
      order_(texture.order()),
      run_count_(texture.run_count()),
      steps_(texture.steps().data()),
      indices_(texture.indices().data()),
      palette_(texture.palette().data()) {
  const uint32_t width = texture.width(), height = texture.height();
  auto cell_count = [&](int bits) {
    return (((uint64_t{width} - 1) >> bits) + 1) * (((uint64_t{height} - 1) >> bits) + 1);
  };
  int bits = options.cell_bits;
  if (bits < 0) {
    bits = 0;
    while (bits < order_ && 3 * cell_count(bits) > texture.run_count()) ++bits;
  }
  cell_bits_ = std::min(bits, order_);
  shortcut_ = options.single_run_shortcut && texture.run_count() < (size_t{1} << 24);
  columns_ = ((width - 1) >> cell_bits_) + 1;
  const size_t rows = ((height - 1) >> cell_bits_) + 1;
  cells_.resize(columns_ * rows);
  const uint32_t last_step = texture.steps().back();
  const uint64_t cell_steps = uint64_t{1} << (2 * cell_bits_);
  size_t several = 0;  // cells of several runs
  for (size_t cy = 0; cy < rows; ++cy) {
    for (size_t cx = 0; cx < columns_; ++cx) {
      // The cell's steps: the aligned block's contiguous range (its top-left texel lies inside
      // the texture, so the range holds texture texels and its start is <= the last step).
      const uint64_t first_step = CellStart(cx, cy);
      const uint64_t end_step = std::min<uint64_t>(first_step + cell_steps - 1, last_step);
      const size_t first = texture.RunOfStep(static_cast<uint32_t>(first_step));
      const size_t last = texture.RunOfStep(static_cast<uint32_t>(end_step));
      Cell& cell = cells_[cy * columns_ + cx];
      cell.first = shortcut_ ? static_cast<uint32_t>((first << 8) | indices_[first])
                             : static_cast<uint32_t>(first);
      cell.last = static_cast<uint32_t>(last);
      several += first != last;
    }
  }
  // Detail records where they fit (12-bit offsets, the shortcut's cell layout) and, unless asked
  // for, only when they are few: at most one per 8 runs keeps the index under about 11 bytes per
  // run (a noisy texture would otherwise get a 68-byte record for nearly every cell).
  const bool fit = shortcut_ && cell_bits_ >= kMinDetailBits && cell_bits_ <= kMaxDetailBits;
  const bool wanted =
      options.details == Options::Details::kAlways ||
      (options.details == Options::Details::kAuto && 8 * several <= texture.run_count());
  if (fit && wanted) {
    for (size_t cy = 0; cy < rows; ++cy) {
      for (size_t cx = 0; cx < columns_; ++cx) {
        Cell& cell = cells_[cy * columns_ + cx];
        if ((cell.first >> 8) == cell.last) continue;
        AddDetail(texture, cell, static_cast<uint32_t>(cx << cell_bits_),
                  static_cast<uint32_t>(cy << cell_bits_), CellStart(cx, cy), cell.first >> 8);
      }
    }
  }
  if (details_.empty()) return;
  // A block of 2^c x 2^c texels is the order-c curve in one of four orientations.
  const uint32_t side = 1u << cell_bits_, block = side * side;
  local_steps_.resize(4 * size_t{block});
  for (uint32_t state = 0; state < 4; ++state) {
    for (uint32_t local = 0; local < block; ++local) {
      uint32_t s = state, x = 0, y = 0;
      for (int level = cell_bits_ - 1; level >= 0; --level) {
        const HilbertChild c = ChildQuadrant(curve_, s, (local >> (2 * level)) & 3u);
        x |= c.xb << level;
        y |= c.yb << level;
        s = c.state;
      }
      local_steps_[state * block + y * side + x] = static_cast<uint16_t>(local);
    }
  }
}

void RunIndex::AddDetail(const PackedTextureView& texture, Cell& cell, uint32_t x0, uint32_t y0,
                         uint64_t start, size_t first) {
  cell.last = kHasDetail | static_cast<uint32_t>(details_.size());
  // The orientation of the block: the curve's descent along the digits of its start.
  uint32_t state = 0;
  for (int level = order_ - 1; level >= cell_bits_; --level)
    state = ChildQuadrant(curve_, state, static_cast<uint32_t>(start >> (2 * level)) & 3u).state;
  details_.push_back(static_cast<uint32_t>(start) | state);
  const int sub_bits = cell_bits_ - 2;
  const uint64_t sub_steps = uint64_t{1} << (2 * sub_bits);
  const uint32_t last_step = texture.steps().back();
  for (uint32_t k = 0; k < 16; ++k) {
    const uint32_t x = x0 + ((k & 3u) << sub_bits), y = y0 + ((k >> 2) << sub_bits);
    if (x >= texture.width() || y >= texture.height()) {
      details_.push_back(indices_[first]);  // no texel of the texture: never read
      continue;
    }
    // As for the cells: the subcell's block is one contiguous range of steps.
    const uint64_t sub_start = StepOf(x, y) & ~(sub_steps - 1);
    const uint64_t end = std::min<uint64_t>(sub_start + sub_steps - 1, last_step);
    const size_t lo = texture.RunOfStep(static_cast<uint32_t>(sub_start));
    const size_t hi = texture.RunOfStep(static_cast<uint32_t>(end));
    details_.push_back(
        static_cast<uint32_t>((lo - first) << 20 | (hi - first) << 8 | indices_[lo]));
  }
}

void RunIndex::ColorsAt(std::span<const uint32_t> xs, std::span<const uint32_t> ys,
                        std::span<uint32_t> colours) const {
  // Three passes over a group, each queueing only what it could not answer: cells of one run,
  // then subcells of one run, then the searches. The first two have no branch per texel.
  constexpr uint32_t kGroup = 256;
  uint32_t queue[kGroup], lo[kGroup], hi[kGroup], start[kGroup];
  for (size_t begin = 0; begin < xs.size(); begin += kGroup) {
    const uint32_t n = static_cast<uint32_t>(std::min<size_t>(kGroup, xs.size() - begin));
    const uint32_t* x = xs.data() + begin;
    const uint32_t* y = ys.data() + begin;
    uint32_t* out = colours.data() + begin;
    uint32_t queued = 0;
    for (uint32_t i = 0; i < n; ++i) {
      const Cell& cell = CellOf(x[i], y[i]);
      const uint32_t first = shortcut_ ? cell.first >> 8 : cell.first;
      // (Without the shortcut `first` holds no palette index; every texel is queued.)
      out[i] = shortcut_ ? palette_[static_cast<uint8_t>(cell.first)] : 0;
      queue[queued] = i;
      lo[queued] = first;
      hi[queued] = cell.last;
      queued += !shortcut_ || first != cell.last;
    }
    // When there are detail records, every cell of several runs has one.
    if (!details_.empty()) {
      uint32_t searched = 0;
      for (uint32_t k = 0; k < queued; ++k) {
        const uint32_t i = queue[k], run = lo[k];
        const uint32_t* detail = &details_[hi[k] & ~kHasDetail];
        const uint32_t sub = detail[1 + SubcellOf(x[i], y[i])];
        out[i] = palette_[static_cast<uint8_t>(sub)];
        queue[searched] = i;
        start[searched] = detail[0];
        lo[searched] = run + (sub >> 20);
        hi[searched] = run + ((sub >> 8) & 0xFFFu);
        searched += lo[searched] != hi[searched];
      }
      queued = searched;
    }
    for (uint32_t k = 0; k < queued; ++k) {
      const uint32_t i = queue[k];
      const uint32_t step = details_.empty() ? StepOf(x[i], y[i]) : LocalStep(start[k], x[i], y[i]);
      out[i] = palette_[indices_[SearchRuns(lo[k], hi[k], step)]];
    }
  }
}

}  // namespace aperture::packed
