#include "texture/packed/run_index.h"

#include <algorithm>

namespace aperture::packed {

RunIndex::RunIndex(const PackedTextureView& texture, const Options& options)
    : curve_(texture.curve()),
      order_(texture.order()),
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
    while (bits < order_ && 2 * cell_count(bits) > texture.run_count()) ++bits;
  }
  cell_bits_ = std::min(bits, order_);
  shortcut_ = options.single_run_shortcut && texture.run_count() < (size_t{1} << 24);
  columns_ = ((width - 1) >> cell_bits_) + 1;
  const size_t rows = ((height - 1) >> cell_bits_) + 1;
  cells_.resize(columns_ * rows);
  const uint32_t last_step = texture.steps().back();
  const uint64_t cell_steps = uint64_t{1} << (2 * cell_bits_);
  for (size_t cy = 0; cy < rows; ++cy) {
    for (size_t cx = 0; cx < columns_; ++cx) {
      // The cell's steps: the aligned block's contiguous range (its top-left texel lies inside
      // the texture, so the range holds texture texels and its start is <= the last step).
      const uint32_t corner =
          StepOf(static_cast<uint32_t>(cx << cell_bits_), static_cast<uint32_t>(cy << cell_bits_));
      const uint64_t first_step = corner & ~(cell_steps - 1);
      const uint64_t end_step = std::min<uint64_t>(first_step + cell_steps - 1, last_step);
      const size_t first = texture.RunOfStep(static_cast<uint32_t>(first_step));
      const size_t last = texture.RunOfStep(static_cast<uint32_t>(end_step));
      Cell& cell = cells_[cy * columns_ + cx];
      cell.first = shortcut_ ? static_cast<uint32_t>((first << 8) | indices_[first])
                             : static_cast<uint32_t>(first);
      cell.last = static_cast<uint32_t>(last);
    }
  }
}

void RunIndex::ColorsAt(std::span<const uint32_t> xs, std::span<const uint32_t> ys,
                        std::span<uint32_t> colours) const {
  constexpr size_t kGroup = 16;
  for (size_t begin = 0; begin < xs.size(); begin += kGroup) {
    const size_t n = std::min(kGroup, xs.size() - begin);
    // Grid cells of the whole group first, so that their cache misses overlap.
    for (size_t i = begin; i < begin + n; ++i)
      __builtin_prefetch(&cells_[size_t{ys[i] >> cell_bits_} * columns_ + (xs[i] >> cell_bits_)]);
    for (size_t i = begin; i < begin + n; ++i) colours[i] = ColorAt(xs[i], ys[i]);
  }
}

}  // namespace aperture::packed
