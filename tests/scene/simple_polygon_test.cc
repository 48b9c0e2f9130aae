// The simplicity check against a brute-force test of every pair of edges, on
// polygons whose vertices sit on a small grid, so touching vertices, collinear edges, vertical
// edges and shared x coordinates (the sweep's hard cases) are everywhere.
#include "scene/simple_polygon.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "scene/triangulate.h"

namespace aperture {
namespace {

double Orient(const Vec2& o, const Vec2& a, const Vec2& b) {
  return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
}

bool OnSegment(const Vec2& a, const Vec2& b, const Vec2& p) {
  return Orient(a, b, p) == 0 && std::min(a.x, b.x) <= p.x && p.x <= std::max(a.x, b.x) &&
         std::min(a.y, b.y) <= p.y && p.y <= std::max(a.y, b.y);
}

bool SegmentsMeet(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d) {
  const double o1 = Orient(a, b, c), o2 = Orient(a, b, d), o3 = Orient(c, d, a),
               o4 = Orient(c, d, b);
  if (((o1 > 0 && o2 < 0) || (o1 < 0 && o2 > 0)) && ((o3 > 0 && o4 < 0) || (o3 < 0 && o4 > 0)))
    return true;
  return OnSegment(a, b, c) || OnSegment(a, b, d) || OnSegment(c, d, a) || OnSegment(c, d, b);
}

// Simple by definition, for polygons without repeated vertices: neighbouring edges share only
// their vertex (no fold back), other edges share nothing.
bool BruteForceSimple(const std::vector<Vec2>& p) {
  const size_t n = p.size();
  for (size_t i = 0; i < n; ++i) {
    const Vec2 &a = p[i], &b = p[(i + 1) % n];
    for (size_t j = i + 1; j < n; ++j) {
      const Vec2 &c = p[j], &d = p[(j + 1) % n];
      const bool neighbours = j == i + 1 || (i == 0 && j == n - 1);
      if (!neighbours) {
        if (SegmentsMeet(a, b, c, d)) return false;
        continue;
      }
      // Neighbours: the far end of one on the other means they overlap.
      const Vec2& shared = j == i + 1 ? b : a;
      const Vec2& far_i = j == i + 1 ? a : b;
      const Vec2& far_j = j == i + 1 ? d : c;
      (void)shared;
      if (OnSegment(a, b, far_j) || OnSegment(c, d, far_i)) return false;
    }
  }
  return true;
}

TEST(SimplePolygon, AgreesWithEveryPairOnGridPolygons) {
  std::mt19937 rng(7);
  int simple = 0, refused = 0;
  for (int trial = 0; trial < 40000; ++trial) {
    const int n = 4 + trial % 9;
    const int grid = 3 + trial % 5;
    std::uniform_int_distribution<int> coordinate(0, grid);
    std::vector<Vec2> poly;
    while (static_cast<int>(poly.size()) < n) {
      const Vec2 v{double(coordinate(rng)), double(coordinate(rng))};
      if (std::find_if(poly.begin(), poly.end(),
                       [&](const Vec2& q) { return q.x == v.x && q.y == v.y; }) == poly.end())
        poly.push_back(v);
    }
    const bool expected = BruteForceSimple(poly);
    const absl::Status got = CheckSimplePolygon(poly);
    ASSERT_EQ(got.ok(), expected) << "trial " << trial << ": " << got;
    (expected ? simple : refused)++;
  }
  // Both answers were exercised often.
  EXPECT_GT(simple, 2000);
  EXPECT_GT(refused, 2000);
}

TEST(SimplePolygon, RefusesTheStarsAndBowTiesOfTheIssue) {
  std::vector<Vec2> pentagram;
  for (int k = 0; k < 5; ++k) {
    const double a = 2 * M_PI * (2 * k) / 5;
    pentagram.push_back({std::cos(a), std::sin(a)});
  }
  EXPECT_FALSE(IsConvex(pentagram));  // every turn is to the left, but it goes round twice
  const absl::Status star = CheckSimplePolygon(pentagram);
  EXPECT_FALSE(star.ok());
  EXPECT_NE(star.message().find("self-intersecting"), std::string::npos) << star;

  const std::vector<Vec2> uneven_bow_tie = {{0, 0}, {3, 2}, {3, 0}, {0, 1}};
  EXPECT_FALSE(CheckSimplePolygon(uneven_bow_tie).ok());
  // A spike out and back along one line, and a vertex touching another edge.
  EXPECT_FALSE(CheckSimplePolygon({{0, 0}, {2, 0}, {2, 2}, {2, 4}, {2, 1}, {0, 2}}).ok());
  EXPECT_FALSE(CheckSimplePolygon({{0, 0}, {4, 0}, {4, 4}, {2, 0}, {0, 4}}).ok());
}

TEST(SimplePolygon, AcceptsConcaveAndDegenerateButSimpleOutlines) {
  EXPECT_TRUE(CheckSimplePolygon({{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}}).ok());  // an L
  // Collinear vertices going straight on, and a repeated vertex.
  EXPECT_TRUE(CheckSimplePolygon({{0, 0}, {1, 0}, {2, 0}, {2, 2}, {2, 2}, {0, 2}}).ok());
  // A big random star: simple, and checked in O(n log n).
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> jitter(0, 0.9), radius(20, 35);
  std::vector<Vec2> star;
  const int n = 200000;
  for (int i = 0; i < n; ++i) {
    const double a = 2 * M_PI * (i + jitter(rng)) / n, r = radius(rng);
    star.push_back({r * std::cos(a), r * std::sin(a)});
  }
  EXPECT_TRUE(CheckSimplePolygon(star).ok());
  std::swap(star[1000], star[150000]);  // two long edges across the star
  EXPECT_FALSE(CheckSimplePolygon(star).ok());
}

}  // namespace
}  // namespace aperture
