#include "cost/frame_statistics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "cost/polygons_per_aperture.h"
#include "scene/triangulate.h"

namespace aperture {
namespace {

// The setting of seed 002's fig. 4: m = 512, l_cp = 3, a = 1 and 2, kappa = 1 and 2,
// F = 1k..64k. Expected values computed by hand from eq. 14-15.
TEST(PolygonsPerAperture, ReproducesThePapersFigureFourSetting) {
  struct Row {
    double a, kappa, faces, square, circle;
  };
  const Row rows[] = {
      {1, 1, 1024, 1.473899, 1.335403}, {1, 1, 65536, 5.009942, 3.855030},
      {1, 2, 4096, 3.344965, 2.952257}, {1, 2, 65536, 7.567362, 5.956292},
      {2, 1, 1024, 1.955611, 1.676942}, {2, 1, 16384, 5.009942, 3.855030},
      {2, 2, 1024, 3.344965, 2.952257}, {2, 2, 65536, 13.634723, 10.305283},
  };
  for (const Row& r : rows) {
    EXPECT_NEAR(PolygonsPerApertureSquare(r.kappa, r.a, 512, 3, r.faces), r.square, 1e-6);
    EXPECT_NEAR(PolygonsPerApertureCircle(r.kappa, r.a, 512, 3, r.faces), r.circle, 1e-6);
  }
}

TEST(PolygonsPerAperture, ShapeFactorOfACircleIsOne) {
  EXPECT_NEAR(ShapeFactor(3.14159265358979 * 4, 2 * 3.14159265358979 * 2), 1.0, 1e-12);
  EXPECT_NEAR(ShapeFactor(1, 4), 2 / std::sqrt(3.14159265358979), 1e-12);  // a square
}

ScreenPolygon Polygon(std::vector<Vec2> vertices) {
  ScreenPolygon p;
  p.vertices.assign(vertices.begin(), vertices.end());
  p.Finalize();
  return p;
}

// A rectangle of sides s and s * ratio turned by 45 degrees (its edges then widen by a / sqrt 2
// under a square filter, the case where eq. 6 is an equality), with a corner at (cx, cy).
ScreenPolygon Diamond(double cx, double cy, double s, double ratio) {
  const double k = 1 / std::sqrt(2.0);
  const Vec2 u{s * k, s * k}, v{-s * ratio * k, s * ratio * k};
  std::vector<Vec2> pts = {
      {cx, cy}, {cx + u.x, cy + u.y}, {cx + u.x + v.x, cy + u.y + v.y}, {cx + v.x, cy + v.y}};
  if (SignedArea(pts) < 0) std::reverse(pts.begin(), pts.end());
  return Polygon(std::move(pts));
}

FrameGeometry Frame(int m) {
  FrameGeometry g;
  g.width = g.height = m;
  return g;
}

TEST(FrameStatistics, EqualFacesMeetTheEstimateWithinFivePercent) {
  for (double ratio : {1.0, 4.0}) {  // shape factors 1.13 and 1.41
    for (double a : {1.0, 2.0}) {
      FrameGeometry g = Frame(512);
      std::mt19937 rng(3);
      std::uniform_real_distribution<double> jitter(0, 1);
      const double s = ratio == 1 ? 9.3 : 6.1;
      for (int j = 0; j < 12; ++j)
        for (int i = 0; i < 12; ++i)
          g.polygons.push_back(
              Diamond(40 + i * 41 + jitter(rng), 5 + j * 41 + jitter(rng), s, ratio));
      const FrameStatistics stats = ComputeFrameStatistics(g, a);
      EXPECT_EQ(stats.faces, 144);
      EXPECT_NEAR(stats.per_face[0].area, s * s * ratio, 1e-9);
      const double measured = MeasurePolygonsPerAperture(g, a);
      EXPECT_NEAR(measured / stats.predicted_square, 1.0, 0.05)
          << "ratio " << ratio << " a " << a << ": measured " << measured << " predicted "
          << stats.predicted_square;
    }
  }
}

TEST(FrameStatistics, UnequalFacesStayBelowTheEstimate) {
  FrameGeometry g = Frame(512);
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> size(2, 18);
  for (int j = 0; j < 12; ++j)
    for (int i = 0; i < 12; ++i)
      g.polygons.push_back(Diamond(40 + i * 40, 5 + j * 40, size(rng), 1));
  const FrameStatistics stats = ComputeFrameStatistics(g, 2);
  EXPECT_LT(MeasurePolygonsPerAperture(g, 2), stats.predicted_square);
}

}  // namespace
}  // namespace aperture
