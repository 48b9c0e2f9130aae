// Builds seed 000's prefiltered table (layout in prefiltered_table.h) from an image with oneTBB.
// Each copy is the periodic texture (piecewise-constant texels) averaged over its box
// parallelogram: first a running-sum box of 2L along the minor axis, then running sums along
// the sheared lines of slope tg over 2H along the major axis: O(N^2 / L) per copy, independent
// of H, never a loop over the aperture. The sums of bands of lines advance column by column
// (table_column_kernels.h, AVX2 when the processor has it), for up to 64 copies of a cell at
// once, so that each column of the minor pass is read from memory once for all of them.
#pragma once

#include <functional>

#include "absl/status/statusor.h"
#include "base/image.h"
#include "texture/prefiltered_table.h"

namespace aperture {

struct TableBuildOptions {
  int threads = 0;  // 0: all cores (the caller's task arena otherwise)
  // Called from the building thread with the fraction of the work done, increasing, last 1.
  std::function<void(double)> progress;
  // Asked between groups of copies and, inside a group's sweep, by each worker thread every 256
  // columns (so it must be thread-safe and cheap: a few hundred times a second at most); true:
  // the build stops and returns Cancelled (a load whose client gave up does not build on for
  // half a minute).
  std::function<bool()> stop;
};

// Images that are not square powers of two are resampled to the next power of two of their
// longer side (OpenImageIO's default resize filter) with a log line saying so.
absl::StatusOr<TableBlock> BuildPrefilteredTable(const Image& image,
                                                 const TableBuildOptions& options = {});

}  // namespace aperture
