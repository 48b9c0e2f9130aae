// The visible part of a light's footprint: its area per cell by edge accumulation against the
// independent clipping of each piece to each cell, and against shapes whose areas are known.
#include "render/visible_footprint.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>
#include <vector>

#include "raster/screen_polygon.h"
#include "scene/vec.h"

namespace aperture {
namespace {

// A regular polygon of `n` vertices and circumradius `r` about (x, y), counter-clockwise on the
// screen (positive signed area, y down), turned by `turn` radians.
std::vector<Vec2> RegularPolygon(int n, double x, double y, double r, double turn) {
  std::vector<Vec2> v(n);
  for (int k = 0; k < n; ++k)
    v[k] = {x + r * std::cos(turn + 2 * kPi * k / n), y + r * std::sin(turn + 2 * kPi * k / n)};
  return v;
}

ScreenPolygon Polygon(std::vector<Vec2> vertices) {
  ScreenPolygon p;
  p.vertices.assign(vertices.begin(), vertices.end());
  p.Finalize();
  return p;
}

// The cells' areas by InRow, the clipping of every piece to every cell.
std::vector<double> AreasByRows(VisibleFootprint& v, double x0, double y0, int columns, int rows) {
  std::vector<double> areas;
  std::vector<CellMoments> row(columns);
  for (int j = 0; j < rows; ++j) {
    v.InRow(x0, y0 + j + 0.5, columns, false, row.data());
    for (const CellMoments& m : row) areas.push_back(m.area);
  }
  return areas;
}

TEST(VisibleFootprintAreas, EqualTheClippedPiecesInEveryCell) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> unit(0, 1);
  double largest_error = 0;
  int cut = 0;
  for (int trial = 0; trial < 500; ++trial) {
    const double cx = 10 + unit(random), cy = 20 + unit(random);
    const double radius = 0.3 + 3 * unit(random);
    VisibleFootprint v;
    const std::vector<Vec2> octagon = RegularPolygon(8, cx, cy, radius, kPi / 8);
    v.Start(octagon);
    // Up to three occluders: triangles and quads across the footprint.
    const int occluders = trial % 4;
    bool in_pieces = true;
    for (int k = 0; k < occluders && in_pieces; ++k)
      in_pieces = v.Subtract(Polygon(RegularPolygon(
          3 + k % 2, cx + radius * (2 * unit(random) - 1), cy + radius * (2 * unit(random) - 1),
          radius * (0.3 + unit(random)), 2 * kPi * unit(random))));
    ASSERT_TRUE(in_pieces);
    cut += occluders > 0 && v.Area() < 0.999 * kPi * radius * radius;
    const double x0 = std::floor(cx - radius) - 0.5, y0 = std::floor(cy - radius) - 0.5;
    const int columns = static_cast<int>(std::ceil(cx + radius - x0)) + 1;
    const int rows = static_cast<int>(std::ceil(cy + radius - y0)) + 1;
    std::vector<double> accumulated(static_cast<size_t>(columns) * rows);
    v.AreasInCells(x0, y0, columns, rows, accumulated.data());
    const std::vector<double> clipped = AreasByRows(v, x0, y0, columns, rows);
    double sum = 0;
    for (size_t i = 0; i < clipped.size(); ++i) {
      largest_error = std::max(largest_error, std::abs(accumulated[i] - clipped[i]));
      sum += accumulated[i];
    }
    EXPECT_NEAR(sum, v.Area(), 1e-12 * radius * radius) << "trial " << trial;
  }
  std::printf("largest difference in a cell's area over 500 footprints: %.3g square pixels\n",
              largest_error);
  EXPECT_LT(largest_error, 1e-12);
  EXPECT_GT(cut, 200);  // most of the occluded footprints lost some of their area
}

TEST(VisibleFootprintAreas, AreKnownForASquareAndAnEdgeAcrossCells) {
  // A square [0.25, 1.75]^2 over the cells [0, 1] x [0, 1] .. [1, 2] x [1, 2]: 0.5625 each.
  VisibleFootprint square;
  const std::array<Vec2, 4> s = {Vec2{0.25, 0.25}, Vec2{1.75, 0.25}, Vec2{1.75, 1.75},
                                 Vec2{0.25, 1.75}};
  square.Start(s);
  ASSERT_NEAR(square.Area(), 2.25, 1e-15);
  std::array<double, 4> areas;
  square.AreasInCells(0, 0, 2, 2, areas.data());
  for (double a : areas) EXPECT_NEAR(a, 0.5625, 1e-15);
  // The triangle (0, 0), (3, 0), (0, 1) over three cells of one row: its height at x is
  // 1 - x / 3, so cell i holds the integral of that over [i, i + 1]: 5/6, 3/6, 1/6.
  VisibleFootprint triangle;
  const std::array<Vec2, 3> t = {Vec2{0, 0}, Vec2{3, 0}, Vec2{0, 1}};
  triangle.Start(t);
  ASSERT_NEAR(triangle.Area(), 1.5, 1e-15);
  std::array<double, 3> row;
  triangle.AreasInCells(0, 0, 3, 1, row.data());
  EXPECT_NEAR(row[0], 5.0 / 6, 1e-15);
  EXPECT_NEAR(row[1], 3.0 / 6, 1e-15);
  EXPECT_NEAR(row[2], 1.0 / 6, 1e-15);
}

}  // namespace
}  // namespace aperture
