// Warnock subdivision: the leaves tile the window exactly, a window nothing
// reaches is one empty leaf, a window one front polygon fills is covered by it, mixed leaves are
// small, and every polygon that reaches a pixel's aperture is listed by that pixel's leaf.
#include "raster/warnock.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

namespace aperture {
namespace {

// A screen polygon at constant depth `depth` (nearer is smaller), its vertices put in the
// order ScreenPolygon wants (edge functions >= 0 inside).
ScreenPolygon Flat(std::vector<Vec2> vertices, double depth, int id) {
  double twice_area = 0;
  for (size_t i = 0; i < vertices.size(); ++i) {
    const Vec2 &a = vertices[i], &b = vertices[(i + 1) % vertices.size()];
    twice_area += a.x * b.y - b.x * a.y;
  }
  if (twice_area < 0) std::reverse(vertices.begin(), vertices.end());
  ScreenPolygon p;
  p.vertices.assign(vertices.begin(), vertices.end());
  p.inv_depth = {0, 0, 1.0 / depth};
  p.scene_polygon = id;
  p.Finalize();
  return p;
}

std::vector<LeafWindow> Subdivide(const FrameGeometry& geometry, AntiAliasing aa,
                                  const PixelRect& window,
                                  const WarnockOptions& options = WarnockOptions{}) {
  std::vector<int> candidates;
  for (int i = 0; i < static_cast<int>(geometry.polygons.size()); ++i) candidates.push_back(i);
  std::vector<LeafWindow> leaves;
  SubdivideWindow(geometry, ShapeOf(aa), options, window, candidates, leaves);
  return leaves;
}

// Every pixel of `window` in exactly one leaf.
void ExpectTiling(const std::vector<LeafWindow>& leaves, const PixelRect& window) {
  std::vector<int> hits(static_cast<size_t>(window.pixels()), 0);
  for (const LeafWindow& leaf : leaves)
    for (int y = leaf.rect.y0; y < leaf.rect.y1; ++y)
      for (int x = leaf.rect.x0; x < leaf.rect.x1; ++x) {
        ASSERT_TRUE(x >= window.x0 && x < window.x1 && y >= window.y0 && y < window.y1);
        ++hits[static_cast<size_t>((y - window.y0) * window.width() + (x - window.x0))];
      }
  for (int h : hits) ASSERT_EQ(h, 1);
}

TEST(Warnock, NothingInTheWindowIsOneEmptyLeaf) {
  FrameGeometry geometry;
  geometry.width = geometry.height = 64;
  geometry.polygons.push_back(Flat({{100, 100}, {120, 100}, {110, 120}}, 5, 0));  // off the window
  const PixelRect window{0, 0, 64, 64};
  const auto leaves = Subdivide(geometry, AntiAliasing::kBox1, window);
  ASSERT_EQ(leaves.size(), 1u);
  EXPECT_EQ(leaves[0].kind, LeafWindow::Kind::kEmpty);
  EXPECT_EQ(leaves[0].rect.pixels(), window.pixels());
}

TEST(Warnock, AFrontPolygonFillingTheWindowCoversIt) {
  FrameGeometry geometry;
  geometry.width = geometry.height = 64;
  geometry.polygons.push_back(Flat({{-10, -10}, {-10, 80}, {80, 80}, {80, -10}}, 10, 0));
  geometry.polygons.push_back(Flat({{-20, -20}, {-20, 90}, {90, 90}, {90, -20}}, 2, 1));  // nearer
  const PixelRect window{0, 0, 64, 64};
  const auto leaves = Subdivide(geometry, AntiAliasing::kBox2, window);
  ExpectTiling(leaves, window);
  for (const LeafWindow& leaf : leaves) {
    EXPECT_EQ(leaf.kind, LeafWindow::Kind::kCovered);
    EXPECT_EQ(leaf.cover, 1);
  }
}

TEST(Warnock, EdgesEndInSmallMixedLeavesThatListWhatReachesThem) {
  FrameGeometry geometry;
  geometry.width = geometry.height = 64;
  geometry.polygons.push_back(Flat({{3.3, 5.1}, {40.7, 60.2}, {58.9, 9.4}}, 4, 0));
  geometry.polygons.push_back(
      Flat({{20.5, 20.5}, {20.5, 50.25}, {50.75, 50.25}, {50.75, 20.5}}, 3, 1));
  const PixelRect window{0, 0, 64, 64};
  WarnockOptions options;
  options.leaf_size = 8;  // below the window's size, so that it is subdivided
  const auto leaves = Subdivide(geometry, AntiAliasing::kBox1, window, options);
  ExpectTiling(leaves, window);
  int mixed = 0;
  for (const LeafWindow& leaf : leaves) {
    if (leaf.kind != LeafWindow::Kind::kMixed) continue;
    ++mixed;
    EXPECT_LE(leaf.rect.width(), options.leaf_size);
    EXPECT_LE(leaf.rect.height(), options.leaf_size);
    // In ascending order, as the candidates came (the cells' nearest-first scan restores it).
    EXPECT_TRUE(std::is_sorted(leaf.polygons.begin(), leaf.polygons.end()));
    // Each polygon reaching the leaf's area is listed (box1: the aperture is the pixel square).
    for (int p = 0; p < 2; ++p) {
      const bool reaches = PolygonOverlapsRect(geometry.polygons[p], leaf.rect.x0, leaf.rect.y0,
                                               leaf.rect.x1, leaf.rect.y1);
      const bool listed =
          std::find(leaf.polygons.begin(), leaf.polygons.end(), p) != leaf.polygons.end();
      if (reaches) {
        EXPECT_TRUE(listed) << "polygon " << p << " at " << leaf.rect.x0 << "," << leaf.rect.y0;
      }
    }
  }
  EXPECT_GT(mixed, 0);
  // A pixel deep inside the nearer square is covered by it, one outside both is empty.
  for (const LeafWindow& leaf : leaves) {
    const auto contains = [&](int x, int y) {
      return x >= leaf.rect.x0 && x < leaf.rect.x1 && y >= leaf.rect.y0 && y < leaf.rect.y1;
    };
    if (contains(35, 35)) {
      EXPECT_EQ(leaf.kind, LeafWindow::Kind::kCovered);
      EXPECT_EQ(leaf.cover, 1);
    }
    if (contains(1, 62)) {
      EXPECT_EQ(leaf.kind, LeafWindow::Kind::kEmpty);
    }
  }
}

// A window more than crowded_polygons polygons reach stops at crowded_leaf_size; one that few
// reach is split down to leaf_size (where its quadrants may still be covered or empty).
TEST(Warnock, CrowdedWindowsStopAtTheCrowdedLeafSize) {
  FrameGeometry geometry;
  geometry.width = geometry.height = 128;
  // Twenty small triangles in the top-left 64 x 64, one long edge through the bottom half.
  for (int k = 0; k < 20; ++k) {
    const double x = 3 + 3 * k, y = 5 + 2.5 * k;
    geometry.polygons.push_back(Flat({{x, y}, {x + 4, y}, {x, y + 4}}, 2 + k, k));
  }
  geometry.polygons.push_back(Flat({{-10, 70}, {140, 100}, {-10, 140}}, 50, 20));
  const PixelRect window{0, 0, 128, 128};
  WarnockOptions options;
  options.leaf_size = 8;
  options.crowded_leaf_size = 64;
  const auto leaves = Subdivide(geometry, AntiAliasing::kBox1, window, options);
  ExpectTiling(leaves, window);
  bool crowded_leaf = false;
  for (const LeafWindow& leaf : leaves) {
    if (leaf.kind != LeafWindow::Kind::kMixed) continue;
    const int size = std::max(leaf.rect.width(), leaf.rect.height());
    if (static_cast<int>(leaf.polygons.size()) > options.crowded_polygons) {
      EXPECT_LE(size, options.crowded_leaf_size);
      crowded_leaf = crowded_leaf || size == 64;
    } else {
      EXPECT_LE(size, options.leaf_size) << leaf.rect.x0 << "," << leaf.rect.y0;
    }
  }
  EXPECT_TRUE(crowded_leaf);  // the crowded corner is one 64 x 64 leaf, not split further
}

}  // namespace
}  // namespace aperture
