#include "raster/cell_coverage.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "raster/polygon_moments.h"
#include "scene/triangulate.h"

namespace aperture {
namespace {

// A screen triangle (counter-clockwise) with a given 1/depth plane.
ScreenPolygon Triangle(Vec2 a, Vec2 b, Vec2 c, ScreenLinear inv_depth) {
  ScreenPolygon p;
  p.vertices = {a, b, c};
  if (SignedArea(p.vertices) < 0) std::swap(p.vertices[1], p.vertices[2]);
  p.Finalize();
  p.inv_depth = inv_depth;
  return p;
}

// Whether polygon k is seen over polygon `best` at (x, y): nearer, or coplanar and drawn later.
bool SeenOver(const std::vector<ScreenPolygon>& polys, int k, int best, double x, double y) {
  const int sign = DepthSign(polys[k].inv_depth.At(x, y), polys[best].inv_depth.At(x, y));
  return sign > 0 ||
         (sign == 0 && DrawOrder(polys[k].layer, k) > DrawOrder(polys[best].layer, best));
}

// Visible area of each polygon in the cell by n x n point samples.
std::vector<double> SampledAreas(const std::vector<ScreenPolygon>& polys, double cx, double cy,
                                 int n) {
  std::vector<double> area(polys.size(), 0);
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const double x = cx - 0.5 + (i + 0.5) / n, y = cy - 0.5 + (j + 0.5) / n;
      int best = -1;
      for (size_t k = 0; k < polys.size(); ++k)
        if (polys[k].Contains(x, y) &&
            (best < 0 || SeenOver(polys, static_cast<int>(k), best, x, y)))
          best = static_cast<int>(k);
      if (best >= 0) area[best] += 1.0 / (double(n) * n);
    }
  }
  return area;
}

TEST(CellCoverage, FullCellIsExactlyOne) {
  std::vector<ScreenPolygon> polys = {Triangle({-10, -10}, {10, -10}, {0, 10}, {0, 0, 1})};
  CellCoverage coverage;
  std::vector<CellPiece> out;
  const int candidates[] = {0};
  coverage.Compute(polys, candidates, 0.5, 0.5, true, out);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].moments.area, 1.0);
  EXPECT_EQ(out[0].moments.mx, 0.0);
}

TEST(CellCoverage, HalfPlaneMomentsAreAnalytic) {
  // Covers x < 0.2 (cell-local) of the cell centred at (0, 0).
  std::vector<ScreenPolygon> polys = {Triangle({0.2, -50}, {0.2, 50}, {-100, 0}, {0, 0, 1})};
  CellCoverage coverage;
  std::vector<CellPiece> out;
  const int candidates[] = {0};
  coverage.Compute(polys, candidates, 0, 0, true, out);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_NEAR(out[0].moments.area, 0.7, 1e-12);
  // integral of x over [-0.5, 0.2] x [-0.5, 0.5] = (0.04 - 0.25) / 2
  EXPECT_NEAR(out[0].moments.mx, (0.04 - 0.25) / 2, 1e-12);
  EXPECT_NEAR(out[0].moments.my, 0, 1e-12);
}

// Random overlapping, interpenetrating triangles: exact areas against dense sampling.
// `snap` > 0 puts vertices on a grid of that step, so that edges run along the cell's sides and
// through its corners (clipping then repeats vertices: a regression of the separating-axis test).
// `max_triangles` and `depth_spread` (depths in [1, 1 + spread]) make crowded cells of pieces at
// many depths, most of whose depth ranges do not meet (a far city block).
// `covers`: that many more triangles covering the whole cell at random depths among the others
// (what they hide is dropped before clipping: CellCoverage::DropHiddenByAFullPolygon).
void CheckRandomTriangles(uint32_t seed, double snap, bool layered = false, int max_triangles = 5,
                          double depth_spread = 1, int covers = 0) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> pos(-1.5, 1.5), slope(-0.3, 0.3),
      depth(1, 1 + depth_spread);
  auto p = [&] {
    Vec2 v{pos(rng), pos(rng)};
    if (snap > 0) v = {std::round(v.x / snap) * snap, std::round(v.y / snap) * snap};
    return v;
  };
  CellCoverage coverage;
  for (int trial = 0; trial < 300; ++trial) {
    std::vector<ScreenPolygon> polys;
    const int count = 2 + trial % (max_triangles - 1);
    for (int k = 0; k < count; ++k) {
      const Vec2 a = p(), b = p(), c = p();
      if (std::abs(SignedArea(std::vector<Vec2>{a, b, c})) < 1e-9) continue;
      // Layered: constant depths, so the painter's order exists; else planes that cross.
      const ScreenLinear w = layered ? ScreenLinear{0, 0, depth(rng)}
                                     : ScreenLinear{slope(rng), slope(rng), depth(rng)};
      polys.push_back(Triangle(a, b, c, w));
    }
    for (int k = 0; k < covers; ++k) {
      const double turn = 2.0943951023931953 * pos(rng);
      auto corner = [&](int i) {
        return Vec2{3 * std::cos(turn + 2.0943951023931953 * i),
                    3 * std::sin(turn + 2.0943951023931953 * i)};
      };
      const ScreenLinear w = layered ? ScreenLinear{0, 0, depth(rng)}
                                     : ScreenLinear{slope(rng), slope(rng), depth(rng)};
      // Inserted among the others, so that a cover is not always first or last.
      const auto at = polys.begin() + static_cast<long>(rng() % (polys.size() + 1));
      polys.insert(at, Triangle(corner(0), corner(1), corner(2), w));
    }
    std::vector<int> candidates(polys.size());
    for (size_t k = 0; k < polys.size(); ++k) candidates[k] = static_cast<int>(k);
    std::vector<CellPiece> out;
    coverage.Compute(polys, candidates, 0, 0, false, out);
    std::vector<double> exact(polys.size(), 0);
    for (const CellPiece& piece : out) exact[piece.polygon] += piece.moments.area;
    const std::vector<double> sampled = SampledAreas(polys, 0, 0, 512);
    for (size_t k = 0; k < polys.size(); ++k)
      ASSERT_NEAR(exact[k], sampled[k], 4e-3) << "trial " << trial << " polygon " << k;
  }
}

TEST(CellCoverage, RandomInterpenetratingTrianglesMatchSampling) { CheckRandomTriangles(1234, 0); }

TEST(CellCoverage, LayeredTrianglesMatchSampling) { CheckRandomTriangles(77, 0, true); }

TEST(CellCoverage, CrowdedCellsOfTrianglesAtManyDepthsMatchSampling) {
  CheckRandomTriangles(4321, 0, false, 30, 6);
  CheckRandomTriangles(4322, 0, true, 30, 6);
}

TEST(CellCoverage, PiecesBehindWholeCellCoversMatchSampling) {
  CheckRandomTriangles(555, 0, true, 8, 2, 2);
  CheckRandomTriangles(556, 0, false, 8, 2, 3);
  CheckRandomTriangles(557, 0, true, 30, 6, 4);
}

// Candidates nearest first (by each polygon's largest 1/depth over its vertices), the scan
// stopping at the first one behind a whole-cell cover: the same pieces as the plain scan (bit for
// bit in most cells, to rounding in the rest), while cells under covers leave candidates untested.
// Planes tilted and flat, covers at random depths among the others, and ties of depth (flat layers
// at equal depths).
TEST(CellCoverage, NearestFirstScanStopsBehindACoverWithTheSamePieces) {
  std::mt19937 rng(91);
  std::uniform_real_distribution<double> pos(-1.5, 1.5), slope(-0.3, 0.3), depth(1, 3);
  CellCoverage coverage;
  int stopped_early = 0, bit_identical = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const bool layered = trial % 2 == 0;
    std::vector<ScreenPolygon> polys;
    const int count = 3 + trial % 25;
    for (int k = 0; k < count; ++k) {
      const bool cover = rng() % 4 == 0;
      const Vec2 a = cover ? Vec2{-9, -9} : Vec2{pos(rng), pos(rng)};
      const Vec2 b = cover ? Vec2{9, -9} : Vec2{pos(rng), pos(rng)};
      const Vec2 c = cover ? Vec2{0, 9} : Vec2{pos(rng), pos(rng)};
      if (std::abs(SignedArea(std::vector<Vec2>{a, b, c})) < 1e-9) continue;
      // Flat layers at one of four depths (ties) or tilted planes.
      const double w = layered ? 1 + 0.5 * static_cast<double>(rng() % 4) : depth(rng);
      polys.push_back(Triangle(
          a, b, c, layered ? ScreenLinear{0, 0, w} : ScreenLinear{slope(rng), slope(rng), w}));
    }
    std::vector<int> in_order(polys.size());
    std::vector<double> nearest(polys.size());
    for (size_t k = 0; k < polys.size(); ++k) {
      in_order[k] = static_cast<int>(k);
      nearest[k] = -INFINITY;
      for (const Vec2& v : polys[k].vertices)
        nearest[k] = std::max(nearest[k], polys[k].inv_depth.At(v.x, v.y));
    }
    std::vector<int64_t> draw_order(polys.size());
    for (size_t k = 0; k < polys.size(); ++k) draw_order[k] = DrawOrder(0, static_cast<int>(k));
    std::vector<int> by_depth = in_order;
    std::sort(by_depth.begin(), by_depth.end(), [&](int a, int b) {
      const uint64_t qa = NearestQuantum(nearest[a]), qb = NearestQuantum(nearest[b]);
      return qa > qb || (qa == qb && a > b);
    });
    for (const Vec2 centre : {Vec2{0, 0}, Vec2{0.7, -0.4}}) {
      std::vector<CellPiece> plain, sorted;
      coverage.Compute(polys, in_order, centre.x, centre.y, true, plain);
      coverage.Compute(polys, by_depth, nearest, draw_order, centre.x, centre.y, true, sorted);
      // Per polygon: the same moments, to rounding (a hidden polygon the plain scan clips may
      // leave a sliver of rounding in the painter's regions).
      std::vector<CellMoments> a(polys.size()), b(polys.size());
      for (const CellPiece& piece : plain) Accumulate(a[piece.polygon], piece.moments);
      for (const CellPiece& piece : sorted) Accumulate(b[piece.polygon], piece.moments);
      bool same = plain.size() == sorted.size();
      for (size_t k = 0; k < polys.size(); ++k) {
        ASSERT_NEAR(a[k].area, b[k].area, 1e-12) << trial << " polygon " << k;
        ASSERT_NEAR(a[k].mx, b[k].mx, 1e-12) << trial << " polygon " << k;
        ASSERT_NEAR(a[k].mxy, b[k].mxy, 1e-12) << trial << " polygon " << k;
        same = same && a[k].area == b[k].area && a[k].mxy == b[k].mxy;
      }
      bit_identical += same;
      // Whether the scan stopped early: a cover in front of the farthest candidate's nearest.
      double cover_far = -INFINITY;
      for (const ScreenPolygon& p : polys)
        if (p.ContainsRect(centre.x - 0.5, centre.y - 0.5, centre.x + 0.5, centre.y + 0.5))
          cover_far =
              std::max(cover_far, p.inv_depth.At(centre.x, centre.y) -
                                      0.5 * (std::abs(p.inv_depth.a) + std::abs(p.inv_depth.b)));
      stopped_early += nearest[by_depth.back()] < cover_far - 1e-6;
    }
  }
  EXPECT_GT(stopped_early, 500);
  EXPECT_GT(bit_identical, 740);  // of 800 cells: rounding differences are the exception
}

TEST(CellCoverage, TrianglesOnCellSidesAndCornersMatchSampling) {
  CheckRandomTriangles(98, 0.25, true);
  CheckRandomTriangles(99, 0.25);
}

// The same by a depth buffer of n x n samples, polygon by polygon over each one's bounding box
// (for cells of thousands of small polygons).
std::vector<double> DepthBufferAreas(const std::vector<ScreenPolygon>& polys, int n) {
  std::vector<double> best(static_cast<size_t>(n) * n, -INFINITY);
  std::vector<int> id(best.size(), -1);
  auto index = [n](double v) {
    return std::clamp(static_cast<int>(std::floor((v + 0.5) * n)), 0, n - 1);
  };
  for (size_t k = 0; k < polys.size(); ++k) {
    const ScreenPolygon& p = polys[k];
    for (int j = index(p.min_y); j <= index(p.max_y); ++j) {
      for (int i = index(p.min_x); i <= index(p.max_x); ++i) {
        const double x = -0.5 + (i + 0.5) / n, y = -0.5 + (j + 0.5) / n;
        const size_t s = static_cast<size_t>(j) * n + i;
        if (!p.Contains(x, y)) continue;
        const double w = p.inv_depth.At(x, y);
        if (id[s] < 0 || SeenOver(polys, static_cast<int>(k), id[s], x, y))
          best[s] = w, id[s] = static_cast<int>(k);
      }
    }
  }
  std::vector<double> area(polys.size(), 0);
  for (int k : id)
    if (k >= 0) area[k] += 1.0 / (double(n) * n);
  return area;
}

// Areas per polygon from Compute against `n` x `n` samples; also checks the areas sum to the
// covered fraction. Returns the largest per-polygon difference.
double WorstAreaError(const std::vector<ScreenPolygon>& polys, int n, CellCoverage& coverage) {
  std::vector<int> candidates(polys.size());
  for (size_t k = 0; k < polys.size(); ++k) candidates[k] = static_cast<int>(k);
  std::vector<CellPiece> out;
  coverage.Compute(polys, candidates, 0, 0, true, out);
  std::vector<double> exact(polys.size(), 0);
  std::vector<int> seen(polys.size(), 0);
  for (const CellPiece& piece : out) {
    exact[piece.polygon] += piece.moments.area;
    ++seen[piece.polygon];
  }
  for (size_t k = 0; k < polys.size(); ++k)
    EXPECT_LE(seen[k], 1) << "a crowded cell gives each polygon one piece; polygon " << k;
  const std::vector<double> sampled = DepthBufferAreas(polys, n);
  double worst = 0;
  for (size_t k = 0; k < polys.size(); ++k)
    worst = std::max(worst, std::abs(exact[k] - sampled[k]));
  return worst;
}

// A cell that 1,000+ pieces reach (a whole scene seen in one pixel). Small triangles
// with crossing depth planes (interpenetrating: no painter's order) plus a ground under them.
TEST(CellCoverage, ThousandsOfInterpenetratingPiecesMatchSampling) {
  std::mt19937 rng(2024);
  std::uniform_real_distribution<double> centre(-0.55, 0.55), offset(-0.06, 0.06), slope(-0.5, 0.5),
      depth(1, 2);
  std::vector<ScreenPolygon> polys;
  polys.push_back(Triangle({-5, -5}, {5, -5}, {0, 5}, {0, 0, 0.5}));  // ground, behind all
  while (polys.size() < 1500) {
    const Vec2 c{centre(rng), centre(rng)};
    const Vec2 a{c.x + offset(rng), c.y + offset(rng)}, b{c.x + offset(rng), c.y + offset(rng)},
        d{c.x + offset(rng), c.y + offset(rng)};
    if (std::abs(SignedArea(std::vector<Vec2>{a, b, d})) < 1e-6) continue;
    polys.push_back(Triangle(a, b, d, {slope(rng), slope(rng), depth(rng)}));
  }
  CellCoverage coverage;
  // 2048^2 samples: a polygon's sampled area errs by about its perimeter / 2048.
  EXPECT_LT(WorstAreaError(polys, 2048, coverage), 1e-3);
}

// Coplanar crowds: a cell that a few hundred overlapping triangles of about its size reach, all
// in one plane (decals 27 deep), on a few planes a hair apart (layers of decals 1 mm apart), and
// with every triangle placed twice at one place: each polygon's area against a depth buffer of
// 2048^2 samples that decides ties by the same rule (the one drawn later is seen).
void CheckCoplanarCrowd(uint32_t seed, int count, int planes, bool copies, double size) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> centre(-0.7, 0.7), corner(-size, size);
  std::vector<ScreenPolygon> polys;
  const ScreenLinear tilted{0.01, -0.02, 1.0};
  while (static_cast<int>(polys.size()) < count) {
    const Vec2 c{centre(rng), centre(rng)};
    const Vec2 a{c.x + corner(rng), c.y + corner(rng)}, b{c.x + corner(rng), c.y + corner(rng)},
        d{c.x + corner(rng), c.y + corner(rng)};
    if (std::abs(SignedArea(std::vector<Vec2>{a, b, d})) < 1e-4) continue;
    // Plane k lies 1e-3 of its depth in front of plane k - 1.
    const int plane = static_cast<int>(rng() % planes);
    ScreenLinear w = tilted;
    w.c += 1e-3 * plane;
    polys.push_back(Triangle(a, b, d, w));
    if (copies) polys.push_back(polys.back());
  }
  CellCoverage coverage;
  EXPECT_LT(WorstAreaError(polys, 2048, coverage), 2e-3)
      << "seed " << seed << ", " << count << " triangles on " << planes << " planes";
}

TEST(CellCoverage, CoplanarCrowdsMatchSampling) {
  CheckCoplanarCrowd(1, 150, 1, false, 0.6);
  CheckCoplanarCrowd(2, 400, 1, false, 0.3);
  CheckCoplanarCrowd(3, 200, 20, false, 0.6);
  CheckCoplanarCrowd(4, 300, 1, true, 0.6);
  CheckCoplanarCrowd(5, 120, 3, true, 1.5);
}

TEST(CellCoverage, ThousandsOfStackedAndFannedPiecesMatchSampling) {
  std::vector<ScreenPolygon> polys;
  // A fan of 1,200 thin triangles meeting at one point inside the cell: every square around the
  // point keeps all of them (the stalled levels of the subdivision).
  const Vec2 hub{0.13, -0.21};
  const int fan = 1200;
  for (int k = 0; k < fan; ++k) {
    const double a0 = 2 * M_PI * k / fan, a1 = 2 * M_PI * (k + 1) / fan;
    polys.push_back(Triangle(hub, {hub.x + 2 * std::cos(a0), hub.y + 2 * std::sin(a0)},
                             {hub.x + 2 * std::cos(a1), hub.y + 2 * std::sin(a1)},
                             {0, 0, 1.0 + 0.001 * (k % 7)}));
  }
  // And 300 squares stacked at distinct depths over the middle (a painter's order).
  for (int k = 0; k < 300; ++k) {
    const double h = 0.05 + 0.001 * k;
    ScreenPolygon p;
    p.vertices = {{-h, -h}, {h, -h}, {h, h}, {-h, h}};
    p.Finalize();
    p.inv_depth = {0, 0, 2.0 + 0.01 * k};
    polys.push_back(p);
  }
  CellCoverage coverage;
  EXPECT_LT(WorstAreaError(polys, 1024, coverage), 2e-3);
}

// Overlapping coplanar pieces (decals, layers of slivers) are ordered, the one drawn later over
// the earlier, as the decomposition and the dense sampling decide a tie: no decomposition (which
// would ask the stop test between its slabs, or cut the cell into quadrants), and the areas of the
// sampling. Flat and tilted planes, with pieces on other planes among them.
TEST(CellCoverage, CoplanarOverlapsTakeTheOneDrawnLastWithoutDecomposing) {
  std::mt19937 rng(91);
  std::uniform_real_distribution<double> pos(-1.2, 1.2);
  for (const ScreenLinear plane : {ScreenLinear{0, 0, 2}, ScreenLinear{0.1, -0.2, 2}}) {
    for (int trial = 0; trial < 20; ++trial) {
      std::vector<ScreenPolygon> polys;
      for (int k = 0; k < 40; ++k) {
        const Vec2 a{pos(rng), pos(rng)}, b{pos(rng), pos(rng)}, c{pos(rng), pos(rng)};
        if (std::abs(SignedArea(std::vector<Vec2>{a, b, c})) < 1e-3) continue;
        // Every fifth on a plane of its own, in front or behind.
        const ScreenLinear w =
            k % 5 == 4 ? ScreenLinear{plane.a, plane.b, plane.c + (k % 10 == 4 ? 0.5 : -0.5)}
                       : plane;
        polys.push_back(Triangle(a, b, c, w));
      }
      std::vector<int> candidates(polys.size());
      for (size_t k = 0; k < polys.size(); ++k) candidates[k] = static_cast<int>(k);
      CellCoverage coverage;
      int asked = 0;
      coverage.SetStop([&] { return ++asked < 0; });
      std::vector<CellPiece> out;
      coverage.Compute(polys, candidates, 0, 0, false, out);
      EXPECT_EQ(asked, 0) << "decomposed or subdivided, trial " << trial;
      std::vector<double> exact(polys.size(), 0);
      for (const CellPiece& piece : out) exact[piece.polygon] += piece.moments.area;
      const std::vector<double> sampled = SampledAreas(polys, 0, 0, 512);
      for (size_t k = 0; k < polys.size(); ++k)
        ASSERT_NEAR(exact[k], sampled[k], 4e-3) << "trial " << trial << " polygon " << k;
    }
  }
}

// Polygons whose depth ranges over the cell are stacked (small triangles drawn over one another,
// each on a plane of its own, some tilted, some covering the cell) are painted from their crossing
// edges directly (CellCoverage::PaintStacked): their areas and first moments, which the tent
// filters weigh, against 512 x 512 samples; and a polygon covering the cell gets the square less
// the moments in front of it.
TEST(CellCoverage, StackedPolygonsAreaAndMomentsMatchSampling) {
  std::mt19937 rng(606);
  std::uniform_real_distribution<double> pos(-1.3, 1.3), tilt(-0.02, 0.02);
  constexpr int kSamples = 512;
  for (int trial = 0; trial < 200; ++trial) {
    std::vector<ScreenPolygon> polys;
    const int count = 2 + trial % 9;
    for (int k = 0; k < count; ++k) {
      const Vec2 a{pos(rng), pos(rng)}, b{pos(rng), pos(rng)}, c{pos(rng), pos(rng)};
      if (std::abs(SignedArea(std::vector<Vec2>{a, b, c})) < 1e-3) continue;
      // Planes a unit of depth apart, tilted by at most 0.02 a unit: stacked over the cell.
      polys.push_back(Triangle(a, b, c, {tilt(rng), tilt(rng), 1.0 + polys.size()}));
    }
    if (trial % 3 == 0)  // a cover behind some of them
      polys.push_back(Triangle({-5, -5}, {5, -5}, {0, 5}, {0, 0, 1.5 + (trial % 4)}));
    std::vector<int> candidates(polys.size());
    for (size_t k = 0; k < polys.size(); ++k) candidates[k] = static_cast<int>(k);
    CellCoverage coverage;
    std::vector<CellPiece> out;
    coverage.Compute(polys, candidates, 0, 0, /*with_moments=*/true, out);
    std::vector<CellMoments> exact(polys.size()), sampled(polys.size());
    for (const CellPiece& piece : out) Accumulate(exact[piece.polygon], piece.moments);
    const double w = 1.0 / (double(kSamples) * kSamples);
    for (int j = 0; j < kSamples; ++j) {
      for (int i = 0; i < kSamples; ++i) {
        const double x = -0.5 + (i + 0.5) / kSamples, y = -0.5 + (j + 0.5) / kSamples;
        int best = -1;
        for (size_t k = 0; k < polys.size(); ++k)
          if (polys[k].Contains(x, y) &&
              (best < 0 || SeenOver(polys, static_cast<int>(k), best, x, y)))
            best = static_cast<int>(k);
        if (best >= 0) Accumulate(sampled[best], {w, w * x, w * y, w * x * y});
      }
    }
    double total = 0;
    for (size_t k = 0; k < polys.size(); ++k) {
      ASSERT_NEAR(exact[k].area, sampled[k].area, 4e-3) << "trial " << trial << " polygon " << k;
      ASSERT_NEAR(exact[k].mx, sampled[k].mx, 2e-3) << "trial " << trial << " polygon " << k;
      ASSERT_NEAR(exact[k].my, sampled[k].my, 2e-3) << "trial " << trial << " polygon " << k;
      ASSERT_NEAR(exact[k].mxy, sampled[k].mxy, 1e-3) << "trial " << trial << " polygon " << k;
      total += exact[k].area;
    }
    if (trial % 3 == 0) {
      EXPECT_NEAR(total, 1.0, 1e-12) << "a cover leaves nothing open";
    }
  }
}

TEST(CellCoverage, StopTestCutsACrowdedCellShort) {
  std::vector<ScreenPolygon> polys;
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> pos(-0.5, 0.5), slope(-0.5, 0.5);
  for (int k = 0; k < 400; ++k)
    polys.push_back(Triangle({pos(rng), pos(rng)}, {pos(rng), pos(rng)}, {pos(rng), pos(rng)},
                             {slope(rng), slope(rng), 2}));
  std::vector<int> candidates(polys.size());
  for (size_t k = 0; k < polys.size(); ++k) candidates[k] = static_cast<int>(k);
  CellCoverage coverage;
  int asked = 0;
  coverage.SetStop([&] { return ++asked >= 3; });
  std::vector<CellPiece> out;
  coverage.Compute(polys, candidates, 0, 0, false, out);
  EXPECT_TRUE(coverage.Stopped());
  EXPECT_EQ(asked, 3);
}

}  // namespace
}  // namespace aperture
