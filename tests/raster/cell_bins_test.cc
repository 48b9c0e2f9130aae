#include "raster/cell_bins.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "raster/cell_coverage.h"
#include "scene/triangulate.h"

namespace aperture {
namespace {

ScreenPolygon Triangle(Vec2 a, Vec2 b, Vec2 c) {
  ScreenPolygon p;
  p.vertices = {a, b, c};
  if (SignedArea(p.vertices) < 0) std::swap(p.vertices[1], p.vertices[2]);
  p.Finalize();
  return p;
}

bool SamePieces(const std::vector<CellPiece>& a, const std::vector<CellPiece>& b) {
  if (a.size() != b.size()) return false;
  for (size_t k = 0; k < a.size(); ++k)
    if (a[k].polygon != b[k].polygon || a[k].moments.area != b[k].moments.area ||
        a[k].moments.mx != b[k].moments.mx || a[k].moments.my != b[k].moments.my ||
        a[k].moments.mxy != b[k].moments.mxy)
      return false;
  return true;
}

// A cell's list is a subsequence of the candidates, holds every polygon Compute finds in the cell,
// and so gives Compute's result bit for bit; and it is shorter than the lists of the polygons
// whose boxes reach the cell (the same box comparisons as CellCoverage::Compute).
TEST(CellBins, EachCellListsWhatReachesItInOrderAndComputeAgreesBitForBit) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> pos(-6, 30), size(-9, 9), depth(0.01, 1);
  for (double offset : {0.0, -0.5}) {
    std::vector<ScreenPolygon> polygons;
    for (int k = 0; k < 300; ++k) {
      const double x = pos(rng), y = pos(rng);
      polygons.push_back(
          Triangle({x, y}, {x + size(rng), y + size(rng)}, {x + size(rng), y + size(rng)}));
      polygons.back().inv_depth = {0, 0, depth(rng)};
    }
    // Sides on cell borders (touching is not reaching), one inside a cell, a thin sliver.
    polygons.push_back(Triangle({3.5, 4.5}, {7.5, 4.5}, {3.5, 9.5}));
    polygons.push_back(Triangle({3, 4}, {7, 4}, {3, 9}));
    polygons.push_back(Triangle({10.1, 10.1}, {10.4, 10.1}, {10.1, 10.3}));
    polygons.push_back(Triangle({2, 5}, {25, 5.000001}, {25, 5.000002}));
    std::vector<int> candidates;
    for (int k = 0; k < 300; k += 2) candidates.push_back(k);
    for (int k = 300; k < static_cast<int>(polygons.size()); ++k) candidates.push_back(k);
    const int x0 = 2, y0 = 3, nx = 17, ny = 9;
    CellBins bins;
    bins.Build(polygons, candidates, x0, y0, offset, nx, ny);
    size_t listed = 0, boxed = 0;
    CellCoverage coverage;
    std::vector<CellPiece> from_all, from_list;
    for (int j = 0; j < ny; ++j) {
      for (int i = 0; i < nx; ++i) {
        const double cx = x0 + i + offset + 0.5, cy = y0 + j + offset + 0.5;
        std::vector<int> in_box;
        for (int c : candidates) {
          const ScreenPolygon& p = polygons[c];
          if (!(p.max_x <= cx - 0.5 || p.min_x >= cx + 0.5 || p.max_y <= cy - 0.5 ||
                p.min_y >= cy + 0.5))
            in_box.push_back(c);
        }
        const std::span<const int> got = bins.Cell(i, j);
        EXPECT_TRUE(std::includes(candidates.begin(), candidates.end(), got.begin(), got.end()))
            << i << " " << j;
        from_all.clear(), from_list.clear();
        coverage.Compute(polygons, candidates, cx, cy, false, from_all);
        coverage.Compute(polygons, got, cx, cy, false, from_list);
        EXPECT_TRUE(SamePieces(from_all, from_list)) << i << " " << j;
        for (const CellPiece& piece : from_all)  // every polygon with a visible piece is listed
          EXPECT_NE(std::find(got.begin(), got.end(), piece.polygon), got.end()) << i << " " << j;
        listed += got.size();
        boxed += in_box.size();
      }
    }
    EXPECT_GT(listed, 500u);         // the grid is busy, not trivially empty
    EXPECT_LT(listed, boxed * 0.8);  // and the strips list fewer cells than the boxes
  }
}

}  // namespace
}  // namespace aperture
