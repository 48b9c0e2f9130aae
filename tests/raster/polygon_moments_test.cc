// The closed-form area of a cell cut by one line (a cell one polygon edge crosses), against values
// known by hand and against the clipped square's area by Green's theorem.
#include "raster/polygon_moments.h"

#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "raster/polygon_clip.h"

namespace aperture {
namespace {

double ClippedArea(double a, double b, double c) {
  std::vector<Vec2> cell = {{-0.5, -0.5}, {0.5, -0.5}, {0.5, 0.5}, {-0.5, 0.5}}, scratch;
  ClipByHalfPlane(cell, a, b, c, scratch);
  return PolygonMoments(cell, false).area;
}

TEST(HalfPlaneCellArea, KnownCuts) {
  EXPECT_DOUBLE_EQ(HalfPlaneCellArea(1, 0, 0), 0.5);       // x >= 0
  EXPECT_DOUBLE_EQ(HalfPlaneCellArea(0, -1, 0.25), 0.75);  // y <= 0.25
  EXPECT_DOUBLE_EQ(HalfPlaneCellArea(1, 1, 0), 0.5);       // the diagonal
  // x + y >= -0.5 leaves out the corner triangle of legs 0.5; x + y >= 0.5 keeps only it.
  EXPECT_DOUBLE_EQ(HalfPlaneCellArea(1, 1, 0.5), 0.875);
  EXPECT_DOUBLE_EQ(HalfPlaneCellArea(1, 1, -0.5), 0.125);
  EXPECT_DOUBLE_EQ(HalfPlaneCellArea(-2, 3, 5), 1);   // the whole cell
  EXPECT_DOUBLE_EQ(HalfPlaneCellArea(-2, 3, -5), 0);  // none of it
  // Nearly axis-parallel: x >= 0.2 tilted by 1e-12, area 0.3 to rounding.
  EXPECT_NEAR(HalfPlaneCellArea(1, 1e-12, -0.2), 0.3, 1e-15);
  EXPECT_NEAR(HalfPlaneCellArea(-1e-13, 1, 0.1), 0.6, 1e-15);
}

TEST(HalfPlaneCellArea, AgreesWithTheClippedSquareOverRandomLines) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> angle(0, 6.283185307179586), offset(-0.8, 0.8);
  std::uniform_int_distribution<int> pick(0, 3);
  double worst = 0;
  for (int i = 0; i < 20000; ++i) {
    const double t = angle(rng);
    double a = std::cos(t), b = std::sin(t);
    if (pick(rng) == 0) a *= 1e-9;  // some nearly axis-parallel lines
    const double c = offset(rng) * (std::abs(a) + std::abs(b));
    worst = std::max(worst, std::abs(HalfPlaneCellArea(a, b, c) - ClippedArea(a, b, c)));
  }
  EXPECT_LT(worst, 1e-14);
}

}  // namespace
}  // namespace aperture
