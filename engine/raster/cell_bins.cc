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

// The x extent of convex `p` within the strip ya <= y <= yb (its edges clipped to the strip), or
// false when it does not reach the strip.
bool StripExtent(const ScreenPolygon& p, double ya, double yb, double& x_min, double& x_max) {
  x_min = INFINITY, x_max = -INFINITY;
  const size_t n = p.vertices.size();
  for (size_t k = 0; k < n; ++k) {
    const Vec2& a = p.vertices[k];
    const Vec2& b = p.vertices[k + 1 == n ? 0 : k + 1];
    const double lo = std::max(std::min(a.y, b.y), ya), hi = std::min(std::max(a.y, b.y), yb);
    if (lo > hi) continue;
    if (a.y == b.y) {
      x_min = std::min({x_min, a.x, b.x}), x_max = std::max({x_max, a.x, b.x});
      continue;
    }
    const double slope = (b.x - a.x) / (b.y - a.y);
    for (double y : {lo, hi}) {
      const double x = a.x + slope * (y - a.y);
      x_min = std::min(x_min, x), x_max = std::max(x_max, x);
    }
  }
  return x_min <= x_max;
}

}  // namespace

void CellBins::Build(std::span<const ScreenPolygon> polygons, std::span<const int> candidates,
                     int x0, int y0, double offset, int nx, int ny) {
  nx_ = nx;
  const size_t cells = static_cast<size_t>(nx) * ny;
  begin_.assign(cells + 1, 0);
  // Each candidate's cells, row by row: within its bounding box's cells, those its part in the
  // row's strip reaches in x. That part's extent is widened by a relative 1e-9 so that rounding
  // can only add cells, never drop one CellCoverage::Compute would keep (it tests each exactly).
  rows_.clear();
  row_begin_.resize(candidates.size() + 1);
  for (size_t k = 0; k < candidates.size(); ++k) {
    row_begin_[k] = rows_.size();
    const ScreenPolygon& p = polygons[candidates[k]];
    int i0, i1, j0, j1;
    AxisRange(p.min_x, p.max_x, x0, offset, nx, i0, i1);
    AxisRange(p.min_y, p.max_y, y0, offset, ny, j0, j1);
    if (i0 >= i1) continue;
    for (int j = j0; j < j1; ++j) {
      const double cy = static_cast<double>(y0 + j) + offset + 0.5;
      double x_min, x_max;
      if (!StripExtent(p, cy - 0.5, cy + 0.5, x_min, x_max)) continue;
      const double margin = 1e-9 * (1 + std::abs(x_min) + std::abs(x_max));
      int a, b;
      AxisRange(x_min - margin, x_max + margin, x0, offset, nx, a, b);
      a = std::max(a, i0), b = std::min(b, i1);
      if (a >= b) continue;
      rows_.push_back({j, a, b});
      for (int i = a; i < b; ++i) ++begin_[static_cast<size_t>(j) * nx + i + 1];
    }
  }
  row_begin_[candidates.size()] = rows_.size();
  // Counting sort: each cell's start, then the items in the candidates' order.
  for (size_t c = 0; c < cells; ++c) begin_[c + 1] += begin_[c];
  items_.resize(begin_[cells]);
  for (size_t k = 0; k < candidates.size(); ++k)
    for (size_t row = row_begin_[k]; row < row_begin_[k + 1]; ++row)
      for (int i = rows_[row].i0; i < rows_[row].i1; ++i)
        items_[begin_[static_cast<size_t>(rows_[row].j) * nx + i]++] = candidates[k];
  // The fill advanced each start to the next cell's: shift them back.
  for (size_t c = cells; c > 0; --c) begin_[c] = begin_[c - 1];
  begin_[0] = 0;
}

}  // namespace aperture
