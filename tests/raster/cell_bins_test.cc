#include "raster/cell_bins.h"

#include <gtest/gtest.h>

#include <random>
#include <vector>

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

// A cell's list must be exactly the candidates, in order, that CellCoverage::Compute's own box
// test keeps there: the same comparisons at every cell, done by brute force here.
TEST(CellBins, EachCellListsExactlyTheBoxesThatReachItInOrder) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> pos(-6, 30), size(0, 9);
  for (double offset : {0.0, -0.5}) {
    std::vector<ScreenPolygon> polygons;
    for (int k = 0; k < 300; ++k) {
      const double x = pos(rng), y = pos(rng);
      polygons.push_back(Triangle({x, y}, {x + size(rng), y + size(rng)}, {x, y + size(rng)}));
    }
    // Boxes with sides on cell borders (touching is not reaching), and one inside a cell.
    polygons.push_back(Triangle({3.5, 4.5}, {7.5, 4.5}, {3.5, 9.5}));
    polygons.push_back(Triangle({3, 4}, {7, 4}, {3, 9}));
    polygons.push_back(Triangle({10.1, 10.1}, {10.4, 10.1}, {10.1, 10.3}));
    std::vector<int> candidates;
    for (int k = 0; k < static_cast<int>(polygons.size()); k += 2) candidates.push_back(k);
    candidates.push_back(static_cast<int>(polygons.size()) - 1);
    const int x0 = 2, y0 = 3, nx = 17, ny = 9;
    CellBins bins;
    bins.Build(polygons, candidates, x0, y0, offset, nx, ny);
    size_t listed = 0;
    for (int j = 0; j < ny; ++j) {
      for (int i = 0; i < nx; ++i) {
        const double cx = x0 + i + offset + 0.5, cy = y0 + j + offset + 0.5;
        std::vector<int> expected;
        for (int c : candidates) {
          const ScreenPolygon& p = polygons[c];
          if (!(p.max_x <= cx - 0.5 || p.min_x >= cx + 0.5 || p.max_y <= cy - 0.5 ||
                p.min_y >= cy + 0.5))
            expected.push_back(c);
        }
        const std::span<const int> got = bins.Cell(i, j);
        EXPECT_EQ(std::vector<int>(got.begin(), got.end()), expected) << i << " " << j;
        listed += expected.size();
      }
    }
    EXPECT_GT(listed, 500u);  // the grid is busy, not trivially empty
  }
}

}  // namespace
}  // namespace aperture
