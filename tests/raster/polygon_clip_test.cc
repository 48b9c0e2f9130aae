// Sutherland-Hodgman clipping against areas known in closed form.
#include "raster/polygon_clip.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

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

namespace aperture {
namespace {

// The painter's one-pass split gives each side exactly what the clip by the line and by its
// negation give, vertices on the line and all (they go to both sides).
TEST(PolygonClip, SplitByLineGivesBothClipsBitForBit) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> coordinate(-0.5, 0.5), angle(0, 6.283185307179586);
  std::uniform_int_distribution<int> pick(0, 7);
  int split = 0;
  for (int round = 0; round < 5000; ++round) {
    // A convex polygon: points on a circle, in order; some on a grid, so that lines through
    // them put vertices exactly on the line.
    std::vector<double> angles(3 + pick(rng));
    for (double& a : angles) a = angle(rng);
    std::sort(angles.begin(), angles.end());
    std::vector<Vec2> polygon;
    for (double a : angles) polygon.push_back({0.4 * std::cos(a), 0.4 * std::sin(a)});
    if (pick(rng) == 0) polygon = {{-0.5, -0.5}, {0.5, -0.5}, {0.5, 0.5}, {-0.5, 0.5}};
    double a = std::cos(angle(rng)), b = std::sin(angle(rng)), c = coordinate(rng);
    if (pick(rng) < 2) {  // through a vertex
      const Vec2& v = polygon[pick(rng) % polygon.size()];
      c = -(a * v.x + b * v.y);
    }
    if (pick(rng) == 0) a = 1, b = 0, c = -polygon[0].x;  // axis-parallel, through a vertex
    Vec2 inside[64], outside[64], expect_in[64], expect_out[64];
    size_t in_count = 0, out_count = 0;
    ASSERT_TRUE(SplitByLine(polygon.data(), polygon.size(), a, b, c, inside, in_count, outside,
                            out_count, 64));
    const size_t expect_in_count =
        ClipByHalfPlane(polygon.data(), polygon.size(), a, b, c, expect_in, 64);
    const size_t expect_out_count =
        ClipByHalfPlane(polygon.data(), polygon.size(), -a, -b, -c, expect_out, 64);
    ASSERT_EQ(in_count, expect_in_count) << round;
    ASSERT_EQ(out_count, expect_out_count) << round;
    for (size_t k = 0; k < in_count; ++k)
      ASSERT_TRUE(inside[k].x == expect_in[k].x && inside[k].y == expect_in[k].y) << round;
    for (size_t k = 0; k < out_count; ++k)
      ASSERT_TRUE(outside[k].x == expect_out[k].x && outside[k].y == expect_out[k].y) << round;
    split += in_count >= 3 && out_count >= 3;
  }
  EXPECT_GT(split, 1000);  // most lines cut the polygon
}

}  // namespace
}  // namespace aperture
