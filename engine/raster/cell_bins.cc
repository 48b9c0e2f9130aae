#include "raster/cell_bins.h"

#include <algorithm>
#include <cmath>

namespace aperture {
namespace {

// The cells [lo, hi) of one axis whose interval (centre +- 0.5, centre = origin + k + offset + 0.5)
// overlaps the open interval (min, max), with the same comparisons as CellCoverage::Compute.
// The estimate from floor/ceil is widened by one and then settled by those comparisons, so the
// rounding of the estimate cannot change the answer.
void AxisRange(double min, double max, int origin, double offset, int n, int& lo, int& hi) {
  auto centre = [&](int k) { return static_cast<double>(origin + k) + offset + 0.5; };
  auto reaches = [&](int k) {
    const double c = centre(k);
    return !(max <= c - 0.5 || min >= c + 0.5);
  };
  if (!(min <= max)) {  // (never for a finalized polygon; keeps the casts below defined)
    lo = hi = 0;
    return;
  }
  const double first = std::floor(min - origin - offset - 1) - 1;
  const double last = std::ceil(max - origin - offset) + 1;
  lo = static_cast<int>(std::clamp(first, 0.0, static_cast<double>(n)));
  hi = static_cast<int>(std::clamp(last + 1, 0.0, static_cast<double>(n)));
  while (lo < hi && !reaches(lo)) ++lo;
  while (hi > lo && !reaches(hi - 1)) --hi;
}

}  // namespace

void CellBins::Build(std::span<const ScreenPolygon> polygons, std::span<const int> candidates,
                     int x0, int y0, double offset, int nx, int ny) {
  nx_ = nx;
  const size_t cells = static_cast<size_t>(nx) * ny;
  begin_.assign(cells + 1, 0);
  ranges_.resize(candidates.size());
  // Counting sort: each cell's count, its start, then the items in the candidates' order.
  for (size_t k = 0; k < candidates.size(); ++k) {
    const ScreenPolygon& p = polygons[candidates[k]];
    Range& r = ranges_[k];
    AxisRange(p.min_x, p.max_x, x0, offset, nx, r.i0, r.i1);
    AxisRange(p.min_y, p.max_y, y0, offset, ny, r.j0, r.j1);
    for (int j = r.j0; j < r.j1; ++j)
      for (int i = r.i0; i < r.i1; ++i) ++begin_[static_cast<size_t>(j) * nx + i + 1];
  }
  for (size_t c = 0; c < cells; ++c) begin_[c + 1] += begin_[c];
  items_.resize(begin_[cells]);
  for (size_t k = 0; k < candidates.size(); ++k) {
    const Range& r = ranges_[k];
    for (int j = r.j0; j < r.j1; ++j)
      for (int i = r.i0; i < r.i1; ++i)
        items_[begin_[static_cast<size_t>(j) * nx + i]++] = candidates[k];
  }
  // The fill advanced each start to the next cell's: shift them back.
  for (size_t c = cells; c > 0; --c) begin_[c] = begin_[c - 1];
  begin_[0] = 0;
}

}  // namespace aperture
