#include "raster/cell_bins.h"

#include <algorithm>
#include <cmath>

#include "base/held_bytes.h"

namespace aperture {
namespace {

// Rounding allowance of the ranges below, relative to the coordinates' size: ranges are widened by
// it, so that they can only gain a cell (which CellCoverage::Compute then finds unreached), never
// lose one.
constexpr double kSlack = 1e-7;

// The cells [lo, hi) of one axis (cell k spans [origin + k + offset, origin + k + offset + 1])
// that may overlap the open interval (min, max), within [0, n).
void AxisRange(double min, double max, int origin, double offset, int n, int& lo, int& hi) {
  const double slack = kSlack * (1 + std::abs(min) + std::abs(max));
  const double from = std::floor(min - slack - origin - offset);
  const double to = std::ceil(max + slack - origin - offset);
  if (!(from <= to)) {  // NaN: never for a finalized polygon, and keeps the casts defined
    lo = hi = 0;
    return;
  }
  lo = static_cast<int>(std::clamp(from, 0.0, static_cast<double>(n)));
  hi = static_cast<int>(std::clamp(to, 0.0, static_cast<double>(n)));
}

}  // namespace

bool CellBins::Build(std::span<const ScreenPolygon> polygons, std::span<const int> candidates,
                     int x0, int y0, double offset, int nx, int ny, size_t max_items) {
  nx_ = nx;
  const size_t cells = static_cast<size_t>(nx) * ny;
  begin_.assign(cells + 1, 0);
  starts_.assign(cells + 1, 0);
  // Each candidate's cells, row by row: the x extent of its part in each row's strip, from its
  // edges, each edge walked over the rows it crosses.
  rows_.clear();
  row_begin_.resize(candidates.size() + 1);
  for (size_t k = 0; k < candidates.size(); ++k) {
    row_begin_[k] = rows_.size();
    const ScreenPolygon& p = polygons[candidates[k]];
    int i0, i1, j0, j1;
    AxisRange(p.min_x, p.max_x, x0, offset, nx, i0, i1);
    AxisRange(p.min_y, p.max_y, y0, offset, ny, j0, j1);
    if (i0 >= i1 || j0 >= j1) continue;
    extent_min_.assign(j1 - j0, INFINITY);
    extent_max_.assign(j1 - j0, -INFINITY);
    const size_t n = p.vertices.size();
    for (size_t e = 0; e < n; ++e) {
      const Vec2& a = p.vertices[e];
      const Vec2& b = p.vertices[e + 1 == n ? 0 : e + 1];
      const double lo = std::min(a.y, b.y), hi = std::max(a.y, b.y);
      int r0, r1;  // the rows whose strips the edge's y range may meet
      AxisRange(lo, hi, y0, offset, ny, r0, r1);
      r0 = std::max(r0, j0), r1 = std::min(r1, j1);
      // A horizontal edge, or one so nearly so that its slope would magnify rounding: its whole x
      // range (the part in each strip lies within it).
      if (std::abs(b.y - a.y) <= 1e-6 * std::abs(b.x - a.x)) {
        const double ex_min = std::min(a.x, b.x), ex_max = std::max(a.x, b.x);
        for (int j = r0; j < r1; ++j) {
          extent_min_[j - j0] = std::min(extent_min_[j - j0], ex_min);
          extent_max_[j - j0] = std::max(extent_max_[j - j0], ex_max);
        }
        continue;
      }
      // The edge's x where it meets each strip's top and bottom (or its ends), each row's top
      // being the row above's bottom: every x computed once.
      const double slope = (b.x - a.x) / (b.y - a.y);
      auto x_at = [&](double y) { return a.x + slope * (y - a.y); };
      double x_top = x_at(std::max(lo, static_cast<double>(y0 + r0) + offset));
      for (int j = r0; j < r1; ++j) {
        const double top = static_cast<double>(y0 + j) + offset;
        const double ya = std::max(lo, top), yb = std::min(hi, top + 1);
        if (ya > yb) continue;  // (only at a range's ends)
        const double x_bottom = x_at(yb);
        double& x_min = extent_min_[j - j0];
        double& x_max = extent_max_[j - j0];
        x_min = std::min({x_min, x_top, x_bottom}), x_max = std::max({x_max, x_top, x_bottom});
        x_top = x_bottom;
      }
    }
    for (int j = j0; j < j1; ++j) {
      const double x_min = extent_min_[j - j0], x_max = extent_max_[j - j0];
      if (!(x_min <= x_max)) continue;  // no part in this row's strip
      int a, b;
      AxisRange(x_min, x_max, x0, offset, nx, a, b);
      a = std::max(a, i0), b = std::min(b, i1);
      if (a >= b) continue;
      rows_.push_back({j, a, b});
      ++starts_[static_cast<size_t>(j) * nx + a];
      --starts_[static_cast<size_t>(j) * nx + b];
    }
  }
  row_begin_[candidates.size()] = rows_.size();
  // Counting sort: each cell's count, the running sum of the runs starting and ending there (a
  // run's end at a row's last cell is the next row's first: cells are counted row after row),
  // then each cell's start, then the items in the candidates' order.
  int covering = 0;
  for (size_t c = 0; c < cells; ++c) {
    covering += starts_[c];
    begin_[c + 1] = begin_[c] + static_cast<size_t>(covering);
  }
  needed_items_ = begin_[cells];
  if (begin_[cells] > max_items) {
    std::fill(begin_.begin(), begin_.end(), 0);
    items_.clear();
    return false;
  }
  items_.resize(begin_[cells]);
  for (size_t k = 0; k < candidates.size(); ++k)
    for (size_t row = row_begin_[k]; row < row_begin_[k + 1]; ++row)
      for (int i = rows_[row].i0; i < rows_[row].i1; ++i)
        items_[begin_[static_cast<size_t>(rows_[row].j) * nx + i]++] = candidates[k];
  // The fill advanced each start to the next cell's: shift them back.
  for (size_t c = cells; c > 0; --c) begin_[c] = begin_[c - 1];
  begin_[0] = 0;
  return true;
}

size_t CellBins::WorkingBytes() const {
  return HeldBytes(begin_, starts_, items_, rows_, row_begin_, extent_min_, extent_max_);
}

}  // namespace aperture
