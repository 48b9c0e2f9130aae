#include "scene/triangulate.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <map>
#include <random>
#include <utility>

namespace aperture {
namespace {

double Orient(const Vec2& o, const Vec2& a, const Vec2& b) {
  return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
}

// A valid triangulation of a simple polygon: n - 2 counter-clockwise triangles whose areas sum to
// the polygon's, each polygon edge used once in the polygon's counter-clockwise direction and
// every other edge twice, once each way (so the triangles meet edge to edge and do not overlap).
void ExpectValidTriangulation(const std::vector<Vec2>& poly) {
  const auto start = std::chrono::steady_clock::now();
  auto triangles = TriangulatePolygon(poly);
  const double ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  ASSERT_TRUE(triangles.ok()) << triangles.status() << " (" << poly.size() << " vertices)";
  const int n = static_cast<int>(poly.size());
  ASSERT_EQ(triangles->size(), poly.size() - 2);
  const bool ccw = SignedArea(poly) > 0;
  double area = 0;
  std::map<std::pair<int, int>, int> directed;
  for (const auto& t : *triangles) {
    const double a = 0.5 * Orient(poly[t[0]], poly[t[1]], poly[t[2]]);
    ASSERT_GE(a, 0) << "clockwise triangle";
    area += a;
    for (int k = 0; k < 3; ++k) ++directed[{t[k], t[(k + 1) % 3]}];
  }
  EXPECT_NEAR(area, std::abs(SignedArea(poly)), 1e-9 * std::abs(SignedArea(poly)));
  for (const auto& [edge, count] : directed) {
    ASSERT_EQ(count, 1) << "edge " << edge.first << "-" << edge.second << " used twice one way";
    const auto [a, b] = edge;
    const bool boundary = ccw ? (b == (a + 1) % n) : (a == (b + 1) % n);
    if (!boundary) {
      ASSERT_EQ(directed.count({b, a}), 1u) << "interior edge " << a << "-" << b << " unmatched";
    }
  }
  for (int i = 0; i < n; ++i) {
    const std::pair<int, int> edge = ccw ? std::pair{i, (i + 1) % n} : std::pair{(i + 1) % n, i};
    ASSERT_EQ(directed.count(edge), 1u) << "polygon edge " << i << " missing";
  }
  std::printf("%d vertices: %.2f ms\n", n, ms);
}

// Star-shaped about the origin (a random radius at a random angle in each of n equal sectors, so
// consecutive vertices are less than half a turn apart): simple, many reflex vertices.
std::vector<Vec2> RandomStar(int n, std::mt19937& rng) {
  std::uniform_real_distribution<double> radius(0.2, 1.0), within(0, 1);
  std::vector<Vec2> poly;
  for (int i = 0; i < n; ++i) {
    const double a = 2 * M_PI * (i + within(rng)) / n, r = radius(rng);
    poly.push_back({r * std::cos(a), r * std::sin(a)});
  }
  return poly;
}

// A comb: teeth on a grid, so many vertices share a y (and an x): the sweep's ties.
std::vector<Vec2> Comb(int teeth) {
  std::vector<Vec2> poly = {{0, 0}, {2.0 * teeth, 0}};
  for (int t = teeth - 1; t >= 0; --t) {
    poly.push_back({2.0 * t + 2, 3});
    poly.push_back({2.0 * t + 1, 3});
    poly.push_back({2.0 * t + 1, 1});
    poly.push_back({2.0 * t, 1});
  }
  return poly;
}

TEST(Triangulate, RandomStarPolygonsOfEverySize) {
  std::mt19937 rng(42);
  for (int n : {4, 5, 6, 7, 10, 17, 50, 200, 1000, 5000}) {
    for (int trial = 0; trial < (n < 100 ? 40 : 3); ++trial) {
      std::vector<Vec2> poly = RandomStar(n, rng);
      ExpectValidTriangulation(poly);
      std::reverse(poly.begin(), poly.end());  // clockwise too
      ExpectValidTriangulation(poly);
    }
  }
}

TEST(Triangulate, GridAlignedPolygonsWithLevelVertices) {
  ExpectValidTriangulation({{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}});  // an L
  ExpectValidTriangulation(Comb(1));
  ExpectValidTriangulation(Comb(7));
  std::vector<Vec2> comb = Comb(300);
  ExpectValidTriangulation(comb);
  // The comb turned a quarter: teeth pointing west, level vertices on x instead.
  for (Vec2& v : comb) v = {-v.y, v.x};
  ExpectValidTriangulation(comb);
  // Collinear vertices along the sides of a square.
  ExpectValidTriangulation({{0, 0}, {1, 0}, {2, 0}, {2, 1}, {2, 2}, {1, 2}, {1, 1}, {0, 2}});
}

TEST(Triangulate, HundredThousandVerticesInMilliseconds) {
  std::mt19937 rng(7);
  const std::vector<Vec2> poly = RandomStar(100000, rng);
  const auto start = std::chrono::steady_clock::now();
  ExpectValidTriangulation(poly);
  // Ear clipping took minutes here; the bound is generous (the benchmark holds the figure).
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 10);
}

TEST(Triangulate, SelfIntersectingInputFailsCleanly) {
  // A bow-tie and random vertex soups: an error or triangles, never a crash or a hang.
  auto bow_tie = TriangulatePolygon({{0, 0}, {2, 2}, {2, 0}, {0, 2}, {-1, 1}});
  EXPECT_FALSE(bow_tie.ok() && bow_tie->size() != 3);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> pos(0, 1);
  for (int trial = 0; trial < 300; ++trial) {
    std::vector<Vec2> soup(4 + trial % 40);
    for (Vec2& v : soup) v = {pos(rng), pos(rng)};
    auto result = TriangulatePolygon(soup);
    if (result.ok()) {
      EXPECT_EQ(result->size(), soup.size() - 2);
      for (const auto& t : *result)
        for (int i : t) EXPECT_TRUE(i >= 0 && i < static_cast<int>(soup.size()));
    } else {
      EXPECT_NE(result.status().message().find("self-intersecting"), std::string::npos);
    }
  }
}

}  // namespace
}  // namespace aperture
