// Which polygons may reach each cell of a grid of unit cells, found once per grid rather than by
// testing every polygon at every cell: a mixed Warnock leaf of 17 x 17 box2 cells holds some 60
// polygons at 100,000 small triangles a frame, of which a cell meets about 3.
//
// A cell's list keeps the order of `candidates` and holds every polygon that CellCoverage::Compute
// would find reaching the cell (and maybe a few that only come within rounding of it, which
// Compute drops), so the coverage it computes from the list is the same, bit for bit, as from all
// the candidates. Each polygon is listed in the cells its part in each row's strip reaches (its
// edges walked over the rows they cross), not in all of its bounding box: a triangle's box holds
// about twice its cells.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "raster/screen_polygon.h"

namespace aperture {

class CellBins {
 public:
  // The grid's cell (i, j), 0 <= i < nx, 0 <= j < ny, is centred at (x0 + i + offset + 0.5,
  // y0 + j + offset + 0.5), each coordinate summed in that order (as the caller computes the
  // centre it passes to CellCoverage::Compute), and spans half a unit each side of it.
  // False (the bins then empty) when the cells' lists would hold more than `max_items` entries
  // in all (a frame's memory budget).
  bool Build(std::span<const ScreenPolygon> polygons, std::span<const int> candidates, int x0,
             int y0, double offset, int nx, int ny, size_t max_items = SIZE_MAX);
  // The bytes its buffers hold, and those its lists of items hold or needed (the last Build).
  size_t WorkingBytes() const;
  size_t ItemBytes() const { return items_.capacity() * sizeof(int); }
  size_t NeededItemBytes() const { return needed_items_ * sizeof(int); }

  // The polygons that may reach cell (i, j), in the candidates' order.
  std::span<const int> Cell(int i, int j) const {
    const size_t c = static_cast<size_t>(j) * nx_ + i;
    return std::span<const int>(items_).subspan(begin_[c], begin_[c + 1] - begin_[c]);
  }

 private:
  int nx_ = 0;
  std::vector<size_t> begin_;  // cell c's items: [begin_[c], begin_[c + 1])
  std::vector<int> starts_;    // runs of cells starting at cell c less those ending before it
  std::vector<int> items_;
  size_t needed_items_ = 0;
  struct RowCells {
    int j, i0, i1;  // cells [i0, i1) of row j
  };
  std::vector<RowCells> rows_;  // candidate k's: [row_begin_[k], row_begin_[k + 1])
  std::vector<size_t> row_begin_;
  std::vector<double> extent_min_, extent_max_;  // a candidate's x extent in each row's strip
};

}  // namespace aperture
