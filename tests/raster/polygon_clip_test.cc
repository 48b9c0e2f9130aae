// Sutherland-Hodgman clipping (issue 25, part 10) against areas known in closed form.
#include "raster/polygon_clip.h"

#include <gtest/gtest.h>

#include <cmath>

namespace aperture {
namespace {

double Area(const std::vector<Vec2>& p) {
  double twice = 0;
  for (size_t i = 0; i < p.size(); ++i) {
    const Vec2 &a = p[i], &b = p[(i + 1) % p.size()];
    twice += a.x * b.y - b.x * a.y;
  }
  return std::abs(twice) / 2;
}

TEST(PolygonClip, AHalfPlaneCutsASquareIntoTheExpectedPiece) {
  std::vector<Vec2> scratch;
  // The unit square cut by x + y >= 1: the upper-right triangle, area 1/2.
  std::vector<Vec2> square = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  ClipByHalfPlane(square, 1, 1, -1, scratch);
  EXPECT_NEAR(Area(square), 0.5, 1e-15);
  for (const Vec2& v : square) EXPECT_GE(v.x + v.y, 1 - 1e-15);

  // Wholly inside: unchanged; wholly outside: nothing.
  std::vector<Vec2> inside = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  ClipByHalfPlane(inside, 1, 0, 5, scratch);
  EXPECT_EQ(inside.size(), 4u);
  EXPECT_NEAR(Area(inside), 1, 1e-15);
  ClipByHalfPlane(inside, 1, 0, -5, scratch);
  EXPECT_TRUE(inside.empty() || Area(inside) == 0);
}

// A polygon that crosses the line many times (what rounding can make of a nearly degenerate one)
// gives more than one vertex over its own count: the fixed-buffer clip reports kClipOverflow
// rather than write past its room, and the vector clip keeps every vertex and crossing.
TEST(PolygonClip, ManyCrossingsOverflowTheFixedClipSafelyAndTheVectorOneKeepsThem) {
  std::vector<Vec2> zigzag;
  for (int i = 0; i < 10; ++i) zigzag.push_back({static_cast<double>(i), i % 2 ? 1e-17 : -1e-17});
  zigzag.push_back({9, 1}), zigzag.push_back({0, 1});
  // y >= 0 keeps the 5 raised points, the 2 top corners and 10 crossings: 17 > 12 + 1.
  Vec2 out[14];
  EXPECT_EQ(ClipByHalfPlane(zigzag.data(), zigzag.size(), 0, 1, 0, out, 14), kClipOverflow);
  Vec2 room[40];
  EXPECT_EQ(ClipByHalfPlane(zigzag.data(), zigzag.size(), 0, 1, 0, room, 40), 17u);
  std::vector<Vec2> scratch;
  ClipByHalfPlane(zigzag, 0, 1, 0, scratch);
  EXPECT_EQ(zigzag.size(), 17u);
  for (const Vec2& v : zigzag) EXPECT_GE(v.y, 0);
}

TEST(PolygonClip, ARectangleKeepsTheOverlapOfATriangle) {
  std::vector<Vec2> scratch;
  // The triangle (0,0), (4,0), (0,4) inside [1, 3] x [0, 1]: the trapezoid of x + y <= 4 there,
  // area = integral over x of min(1, 4 - x) = 2.
  std::vector<Vec2> triangle = {{0, 0}, {4, 0}, {0, 4}};
  ClipToRect(triangle, 1, 0, 3, 1, scratch);
  EXPECT_NEAR(Area(triangle), 2, 1e-14);
  // A rectangle that misses it entirely.
  std::vector<Vec2> missed = {{0, 0}, {4, 0}, {0, 4}};
  ClipToRect(missed, 5, 5, 6, 6, scratch);
  EXPECT_NEAR(Area(missed), 0, 1e-15);
}

TEST(PolygonClip, APlaneCutsA3DPolygon) {
  std::vector<Vec3> scratch;
  // The square z = -1 .. -3 in the x-z plane, cut by the near plane z <= -2 (n = (0,0,-1), d = -2).
  std::vector<Vec3> quad = {{0, 0, -1}, {1, 0, -1}, {1, 0, -3}, {0, 0, -3}};
  ClipByPlane(quad, {0, 0, -1}, -2, scratch);
  ASSERT_EQ(quad.size(), 4u);
  for (const Vec3& v : quad) {
    EXPECT_LE(v.z, -2 + 1e-15);
    EXPECT_GE(v.z, -3 - 1e-15);
  }
}

}  // namespace
}  // namespace aperture
