// Seed 003's fragments on hand-computed quads, the level of eq. 9, child fragments at the
// unit-texture borders, and the measured relative area error against the requested delta.
#include "trace/pixel_fragments.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "testing/grazing_plane.h"
#include "trace/projection_integral.h"

namespace aperture {
namespace {

double TotalArea(const std::vector<TexRect>& rects) {
  double a = 0;
  for (const TexRect& r : rects) a += r.Area();
  return a;
}

// True when (x, z) lies in some rectangle.
bool Covered(const std::vector<TexRect>& rects, double x, double z) {
  for (const TexRect& r : rects)
    if (x >= r.x0 && x <= r.x1 && z >= r.z0 && z <= r.z1) return true;
  return false;
}

// Convex quad containment (either orientation).
bool InQuad(const std::array<TexPoint, 4>& q, double x, double z) {
  int pos = 0, neg = 0;
  for (int e = 0; e < 4; ++e) {
    const TexPoint &p = q[e], &r = q[(e + 1) % 4];
    const double c = (r.x - p.x) * (z - p.z) - (r.z - p.z) * (x - p.x);
    pos += c > 0, neg += c < 0;
  }
  return pos == 0 || neg == 0;
}

// Fragments must cover the quad and not overlap (seed 003's principles 1 and 2).
void ExpectCoverAndDisjoint(const std::array<TexPoint, 4>& q, const FragmentSet& set) {
  std::mt19937 rng(3);
  double x0 = q[0].x, x1 = x0, z0 = q[0].z, z1 = z0;
  for (const TexPoint& p : q)
    x0 = std::min(x0, p.x), x1 = std::max(x1, p.x), z0 = std::min(z0, p.z), z1 = std::max(z1, p.z);
  std::uniform_real_distribution<double> ux(x0, x1), uz(z0, z1);
  for (int n = 0; n < 2000; ++n) {
    const double x = ux(rng), z = uz(rng);
    if (InQuad(q, x, z)) {
      ASSERT_TRUE(Covered(set.fragments, x, z)) << x << "," << z;
    }
  }
  for (size_t a = 0; a < set.fragments.size(); ++a)
    for (size_t b = a + 1; b < set.fragments.size(); ++b) {
      const TexRect &r = set.fragments[a], &s = set.fragments[b];
      const double ox = std::min(r.x1, s.x1) - std::max(r.x0, s.x0);
      const double oz = std::min(r.z1, s.z1) - std::max(r.z0, s.z0);
      ASSERT_FALSE(ox > 1e-15 && oz > 1e-15) << "fragments " << a << " and " << b << " overlap";
    }
  EXPECT_NEAR(TotalArea(set.fragments), set.area, 1e-15);
  EXPECT_GE(set.area, set.quad_area * (1 - 1e-12));
}

TEST(FragmentLevel, IsEquationNine) {
  // k = ceil(-log2(delta S / P) - 1): S = 0.04, P = 0.8, delta = 0.1 -> -log2(0.005) - 1 = 6.64.
  EXPECT_EQ(FragmentLevel(0.1, 0.04, 0.8), 7);
  // A unit square with delta = 0.5: -log2(0.125) - 1 = 2 exactly.
  EXPECT_EQ(FragmentLevel(0.5, 1, 4), 2);
  // Huge quads get coarse (negative) levels.
  EXPECT_EQ(FragmentLevel(0.5, 4096, 256), -4);
}

TEST(PixelFragments, AxisAlignedRectangleIsCoveredExactly) {
  const std::array<TexPoint, 4> q{{{0.1, 0.2}, {0.3, 0.2}, {0.3, 0.4}, {0.1, 0.4}}};
  FragmentOptions opt;
  opt.rule = FragmentLevelRule::kEquationNine;  // the paper's construction, as laid out
  opt.delta = 0.1;
  FragmentSet set;
  BuildFragments(q, opt, &set);
  EXPECT_EQ(set.level, 7);
  EXPECT_NEAR(set.quad_area, 0.04, 1e-15);
  EXPECT_NEAR(set.quad_perimeter, 0.8, 1e-15);
  // Columns 12 (x = 12.8 / 128) .. 38 (38.4 / 128): 27 strips, each the rectangle's part.
  ASSERT_EQ(set.fragments.size(), 27u);
  EXPECT_TRUE(set.columns);  // a tie keeps Gx
  EXPECT_NEAR(set.area, 0.04, 1e-15);
  EXPECT_DOUBLE_EQ(set.fragments.front().x0, 0.1);
  EXPECT_DOUBLE_EQ(set.fragments.front().x1, 13.0 / 128);
  EXPECT_DOUBLE_EQ(set.fragments.back().x0, 38.0 / 128);
  EXPECT_DOUBLE_EQ(set.fragments.back().x1, 0.3);
  for (const TexRect& r : set.fragments) {
    EXPECT_DOUBLE_EQ(r.z0, 0.2);
    EXPECT_DOUBLE_EQ(r.z1, 0.4);
  }
  ExpectCoverAndDisjoint(q, set);
}

TEST(PixelFragments, DiamondRotated45Degrees) {
  // Half-diagonal h = 8 l with l = 1/128 (k = 7 for delta = 0.2: S = 128 l^2, P = 32 sqrt2 l,
  // -log2(0.2 S / P) - 1 = 6.82). Column m of the left half spans x in [0.5 - h + m l, + l] and
  // z in 0.5 -+ (m + 1) l, so the 16 columns cover 2 * 2 l^2 (1 + ... + 8) = 144 l^2 against the
  // diamond's 128 l^2: relative error 1/8, under delta.
  const double l = 1.0 / 128, h = 8 * l;
  const std::array<TexPoint, 4> q{{{0.5 - h, 0.5}, {0.5, 0.5 - h}, {0.5 + h, 0.5}, {0.5, 0.5 + h}}};
  FragmentOptions opt;
  opt.rule = FragmentLevelRule::kEquationNine;  // the paper's construction, as laid out
  opt.delta = 0.2;
  FragmentSet set;
  BuildFragments(q, opt, &set);
  EXPECT_EQ(set.level, 7);
  EXPECT_NEAR(set.quad_area, 128 * l * l, 1e-15);
  ASSERT_EQ(set.fragments.size(), 16u);
  EXPECT_NEAR(set.area, 144 * l * l, 1e-15);
  for (int m = 0; m < 8; ++m) {
    const TexRect& r = set.fragments[m];
    EXPECT_DOUBLE_EQ(r.x0, 0.5 - h + m * l);
    EXPECT_DOUBLE_EQ(r.x1, 0.5 - h + (m + 1) * l);
    EXPECT_NEAR(r.z0, 0.5 - (m + 1) * l, 1e-15);
    EXPECT_NEAR(r.z1, 0.5 + (m + 1) * l, 1e-15);
  }
  EXPECT_LE(set.area / set.quad_area - 1, opt.delta);
  ExpectCoverAndDisjoint(q, set);
}

TEST(PixelFragments, LongSliverKeepsTheColumns) {
  // A parallelogram 0.8 long, 0.01 thick, rising 0.02 over its length: k = 10 for delta = 0.1.
  // Each column's rectangle is the thickness plus the rise over one column, 0.025 l; the rows
  // (Gz) would each span a long stretch, so Gx is kept.
  const std::array<TexPoint, 4> q{{{0.1, 0.5}, {0.9, 0.52}, {0.9, 0.53}, {0.1, 0.51}}};
  FragmentOptions opt;
  opt.rule = FragmentLevelRule::kEquationNine;  // the paper's construction, as laid out
  opt.delta = 0.1;
  FragmentSet set;
  BuildFragments(q, opt, &set);
  ASSERT_EQ(set.level, 10);
  const double l = 1.0 / 1024;
  EXPECT_TRUE(set.columns);
  EXPECT_EQ(set.fragments.size(), 820u);  // columns 102 .. 921
  // Interior columns: height 0.01 + 0.025 l; the two end columns are partial.
  const TexRect& mid = set.fragments[400];
  EXPECT_NEAR(mid.z1 - mid.z0, 0.01 + 0.025 * l, 1e-14);
  // Every column of width w covers w (0.01 + 0.025 w): 818 whole ones and the two ends.
  const double w1 = 103 * l - 0.1, w2 = 0.9 - 921 * l;
  EXPECT_NEAR(set.area, 0.8 * 0.01 + 0.025 * (818 * l * l + w1 * w1 + w2 * w2), 1e-15);
  EXPECT_LE(set.area / set.quad_area - 1, opt.delta);
  ExpectCoverAndDisjoint(q, set);
  // The same sliver turned by 90 degrees keeps the rows.
  std::array<TexPoint, 4> t;
  for (int i = 0; i < 4; ++i) t[i] = {q[i].z, q[i].x};
  FragmentSet rows;
  BuildFragments(t, opt, &rows);
  EXPECT_FALSE(rows.columns);
  EXPECT_NEAR(rows.area, set.area, 1e-12);
}

// The per-axis rule on the same sliver: a few dozen columns instead of 820, within delta; turned
// by 90 degrees, as many rows.
TEST(PixelFragments, PerAxisRuleCoversALongSliverWithFewFragmentsWithinDelta) {
  const std::array<TexPoint, 4> q{{{0.1, 0.5}, {0.9, 0.52}, {0.9, 0.53}, {0.1, 0.51}}};
  FragmentOptions opt;
  opt.delta = 0.1;
  FragmentSet set;
  BuildFragments(q, opt, &set);
  EXPECT_LE(set.area / set.quad_area - 1, opt.delta);
  EXPECT_LE(set.fragments.size(), 64u);
  EXPECT_GE(set.fragments.size(), 8u);
  ExpectCoverAndDisjoint(q, set);
  std::array<TexPoint, 4> t;
  for (int i = 0; i < 4; ++i) t[i] = {q[i].z, q[i].x};
  FragmentSet turned;
  BuildFragments(t, opt, &turned);
  EXPECT_EQ(turned.fragments.size(), set.fragments.size());
  EXPECT_NEAR(turned.area, set.area, 1e-12);
  ExpectCoverAndDisjoint(t, turned);
}

// Every quad within delta, not only on average: random parallelograms of any angle, sides 10^-4
// to 10^-1 apart by up to 30x, unless max_cells caps the level (a thin quad at 45 degrees needs
// about (its bounding box / its area) / delta rectangles, axis-parallel as they are).
TEST(PixelFragments, PerAxisRuleKeepsEveryQuadWithinDelta) {
  std::mt19937 rng(29);
  std::uniform_real_distribution<double> u(-1, 1), angle(0, M_PI), log_len(-4, -1),
      log_ratio(-1.5, 1.5);
  FragmentOptions opt;
  opt.delta = 0.05;
  FragmentSet set;
  int quads = 0, capped = 0;  // capped: over delta at max_cells
  double fragments = 0;
  for (int n = 0; n < 3000; ++n) {
    const double a = angle(rng), b = angle(rng);
    const double la = std::pow(10.0, log_len(rng)), lb = la * std::pow(10.0, log_ratio(rng));
    const TexPoint o{u(rng), u(rng)};
    const TexPoint e{la * std::cos(a), la * std::sin(a)}, f{lb * std::cos(b), lb * std::sin(b)};
    if (std::abs(e.x * f.z - e.z * f.x) < 0.05 * la * lb) continue;
    const std::array<TexPoint, 4> q{
        {o, {o.x + e.x, o.z + e.z}, {o.x + e.x + f.x, o.z + e.z + f.z}, {o.x + f.x, o.z + f.z}}};
    BuildFragments(q, opt, &set);
    ++quads;
    fragments += static_cast<double>(set.fragments.size());
    if (set.area / set.quad_area - 1 <= opt.delta) continue;
    // Over delta only where no finer level was allowed.
    double x0 = q[0].x, x1 = x0, z0 = q[0].z, z1 = z0;
    for (const TexPoint& p : q)
      x0 = std::min(x0, p.x), x1 = std::max(x1, p.x), z0 = std::min(z0, p.z),
      z1 = std::max(z1, p.z);
    const double along = set.columns ? x1 - x0 : z1 - z0;
    ASSERT_GT(along * std::ldexp(1.0, set.level + 1), opt.max_cells) << "quad " << n;
    ++capped;
  }
  EXPECT_GT(quads, 2000);
  EXPECT_LT(capped, quads / 20);
  std::printf("%d quads, %.1f fragments each, %d over delta at the cap\n", quads, fragments / quads,
              capped);
}

// The bound on DESIGN.md's grazing plane where it is hardest: every pixel of the 16 rows next to
// the horizon (projections hundreds of texels long), with the default work bound of 1,024 grid
// columns a quad. A pixel over delta must be one whose level that bound capped (the long, thin
// projections at the sides of the view run diagonally: axis-parallel rectangles need about
// (bounding box / area) / delta of them); at the default delta the mean stays within it.
TEST(PixelFragments, EveryPixelNextToTheHorizonIsWithinDelta) {
  for (double delta : {0.05, 0.1}) {
    FragmentOptions opt;
    opt.delta = delta;
    FragmentSet set;
    double error_sum = 0, fragments = 0;
    int quads = 0, over = 0;
    for (double pitch : {5.0, 20.0, 60.0}) {
      GrazingPlaneView view;
      view.pitch_deg = pitch;
      const int first = FirstMeasuredRow(view);
      for (int j = first; j < first + 16; ++j)
        for (int i = 0; i < view.width; ++i) {
          std::array<TexPoint, 4> q;
          const double cx[4] = {0, 1, 1, 0}, cy[4] = {0, 0, 1, 1};
          bool ok = true;
          for (int c = 0; c < 4; ++c)
            ok = ok && GroundPoint(view, i + cx[c], j + cy[c], &q[c].x, &q[c].z);
          ASSERT_TRUE(ok) << "row " << j;
          BuildFragments(q, opt, &set);
          const double error = set.area / set.quad_area - 1;
          if (error > delta) {
            double x0 = q[0].x, x1 = x0, z0 = q[0].z, z1 = z0;
            for (const TexPoint& p : q)
              x0 = std::min(x0, p.x), x1 = std::max(x1, p.x), z0 = std::min(z0, p.z),
              z1 = std::max(z1, p.z);
            const double along = set.columns ? x1 - x0 : z1 - z0;
            ASSERT_GT(along * std::ldexp(1.0, set.level + 1), opt.max_cells)
                << "pitch " << pitch << ", pixel " << i << ", " << j;
            ++over;
          }
          error_sum += error;
          fragments += static_cast<double>(set.fragments.size());
          ++quads;
        }
    }
    std::printf(
        "delta %.2f: %d pixels next to the horizon, mean error %.4f, %d over delta, %.1f "
        "fragments\n",
        delta, quads, error_sum / quads, over, fragments / quads);
    if (delta == FragmentOptions{}.delta) {
      EXPECT_LE(error_sum / quads, delta);
    }
  }
}

TEST(PixelFragments, ChildFragmentsAtUnitTextureBorders) {
  // [0.9, 1.2] x [-0.15, 0.1] crosses x = 1 and z = 0: four children in [0, 1]^2.
  std::vector<TexRect> children;
  ChildFragments({0.9, -0.15, 1.2, 0.1}, &children);
  ASSERT_EQ(children.size(), 4u);
  EXPECT_NEAR(TotalArea(children), 0.3 * 0.25, 1e-15);
  const TexRect expect[4] = {
      {0.9, 0.85, 1.0, 1.0}, {0.0, 0.85, 0.2, 1.0}, {0.9, 0.0, 1.0, 0.1}, {0.0, 0.0, 0.2, 0.1}};
  for (int i = 0; i < 4; ++i) {
    EXPECT_NEAR(children[i].x0, expect[i].x0, 1e-15);
    EXPECT_NEAR(children[i].z0, expect[i].z0, 1e-15);
    EXPECT_NEAR(children[i].x1, expect[i].x1, 1e-15);
    EXPECT_NEAR(children[i].z1, expect[i].z1, 1e-15);
  }
  // A fragment over three whole periods along x.
  children.clear();
  ChildFragments({-1.5, 2.25, 1.75, 2.5}, &children);
  EXPECT_EQ(children.size(), 4u);
  EXPECT_NEAR(TotalArea(children), 3.25 * 0.25, 1e-15);
  for (const TexRect& c : children) {
    EXPECT_GE(c.x0, 0.0);
    EXPECT_LE(c.x1, 1.0);
    EXPECT_GE(c.z0, 0.0);
    EXPECT_LE(c.z1, 1.0);
  }
}

Image Noise(int n, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0, 1);
  Image img(n, n);
  for (Rgba& t : img.texels()) t = {u(rng), u(rng), u(rng), 1};
  return img;
}

TEST(ProjectionIntegral, RectangleAcrossTheWrapIsTheTextureMean) {
  // An axis-aligned quad is covered exactly, so its colour is the texture's mean over it, here
  // across the texture's wrap; the same quad 5000 periods away gives the same colour.
  const Image img = Noise(64, 9);
  const SummedAreaTable sat(img, 4);
  ProjectionIntegrator integrator({});
  const std::array<TexPoint, 4> q{{{0.9, -0.15}, {1.2, -0.15}, {1.2, 0.1}, {0.9, 0.1}}};
  const Rgba got = integrator.Color(q, sat);
  const auto want = sat.IntegratePeriodic(0.9 * 64, -0.15 * 64, 1.2 * 64, 0.1 * 64);
  const double area = 0.3 * 0.25 * 64 * 64;
  EXPECT_NEAR(got.r, want[0] / area, 1e-6);
  EXPECT_NEAR(got.g, want[1] / area, 1e-6);
  EXPECT_NEAR(got.b, want[2] / area, 1e-6);
  std::array<TexPoint, 4> far = q;
  for (TexPoint& p : far) p.x += 5000, p.z -= 3000;
  const Rgba got_far = integrator.Color(far, sat);
  EXPECT_NEAR(got_far.r, got.r, 1e-6);
  EXPECT_NEAR(got_far.b, got.b, 1e-6);
}

TEST(ProjectionIntegral, FragmentsOverManyPeriodsEqualTheSumOfTheirChildren) {
  // A rotated quad 7 repeats long: at its (coarse, k < 0 or small) level the fragments span
  // several unit textures and are integrated period-wise; the same fragments cut into child
  // fragments and summed one by one must give the same colour.
  const Image img = Noise(16, 12);
  const SummedAreaTable sat(img, 3);
  const std::array<TexPoint, 4> q{{{0.3, 0.2}, {6.1, 4.3}, {5.2, 5.6}, {-0.6, 1.4}}};
  FragmentOptions opt;
  opt.delta = 0.5;
  opt.exact_steps = 0;  // the fragments, not the exact integral
  FragmentSet set;
  BuildFragments(q, opt, &set);
  bool wide = false;
  double sum = 0;
  for (const TexRect& f : set.fragments) {
    wide = wide || f.x1 - f.x0 > 2 || f.z1 - f.z0 > 2;
    std::vector<TexRect> children;
    ChildFragments(f, &children);
    for (const TexRect& c : children)
      sum += sat.Integrate(c.x0 * 16, c.z0 * 16, c.x1 * 16, c.z1 * 16)[0];
  }
  ASSERT_TRUE(wide) << "level " << set.level;
  ProjectionIntegrator integrator(opt);
  EXPECT_NEAR(integrator.Color(q, sat).r, sum / (set.area * 256), 1e-6);
}

TEST(ProjectionIntegral, DiamondMatchesItsCoverAndAConstantTextureIsExact) {
  // The diamond's colour is the mean over its 16 column rectangles, checked rectangle by
  // rectangle with the table's own periodic integral.
  const Image img = Noise(32, 10);
  const SummedAreaTable sat(img, 3);
  const double l = 1.0 / 128, h = 8 * l;
  const std::array<TexPoint, 4> q{{{0.5 - h, 0.5}, {0.5, 0.5 - h}, {0.5 + h, 0.5}, {0.5, 0.5 + h}}};
  FragmentOptions opt;
  opt.delta = 0.2;
  opt.exact_steps = 0;  // seed 003's fragments, not the exact integral
  ProjectionIntegrator integrator(opt);
  FragmentStats stats;
  const Rgba got = integrator.Color(q, sat, &stats);
  double sum = 0;
  for (int m = 0; m < 16; ++m) {
    const double x0 = 0.5 - h + m * l, hz = (m < 8 ? m + 1 : 16 - m) * l;
    sum += sat.IntegratePeriodic(x0 * 32, (0.5 - hz) * 32, (x0 + l) * 32, (0.5 + hz) * 32)[0];
  }
  EXPECT_NEAR(got.r, sum / (144 * l * l * 32 * 32), 1e-6);
  EXPECT_EQ(stats.quads, 1);
  EXPECT_EQ(stats.fragments, 16);
  EXPECT_NEAR(stats.MeanRelativeError(), 0.125, 1e-12);

  const Image grey(16, 16, {0.25f, 0.5f, 0.75f, 1});
  const SummedAreaTable flat(grey, 3);
  const std::array<TexPoint, 4> skew{{{0.3, 0.7}, {3.9, 1.1}, {4.2, 1.3}, {0.2, 0.75}}};
  const Rgba c = integrator.Color(skew, flat);
  EXPECT_NEAR(c.r, 0.25, 1e-9);
  EXPECT_NEAR(c.g, 0.5, 1e-9);
  EXPECT_NEAR(c.b, 0.75, 1e-9);
}

TEST(ProjectionIntegral, MeasuredAreaErrorIsAtMostDelta) {
  // seed 003's acceptance: the mean S_fragments / S_quad - 1 over the pixel projections of the
  // grazing plane (5, 20 and 60 degrees) and over random parallelograms is at most delta.
  const Image img(8, 8, {1, 1, 1, 1});
  const SummedAreaTable sat(img, 1);
  // Both level rules (the default per-axis bound, and the paper's eq. 9 for comparison).
  for (auto rule : {FragmentLevelRule::kPerAxisBound, FragmentLevelRule::kEquationNine})
    for (double delta : {0.02, 0.05, 0.1, 0.25}) {
      FragmentOptions opt;
      opt.rule = rule;
      opt.delta = delta;
      opt.exact_steps = 0;  // the fragments' own error
      // The work bound of 1,024 columns a quad caps the level of the random slivers (aspect up to
      // 1000 at any angle) before delta = 0.02 is reached; this test is about the level rules.
      opt.max_cells = 4096;
      ProjectionIntegrator integrator(opt);
      FragmentStats stats;
      for (double pitch : {5.0, 20.0, 60.0}) {
        GrazingPlaneView view;
        view.pitch_deg = pitch;
        for (int j = FirstMeasuredRow(view); j < view.height; j += 37)
          for (int i = 0; i < view.width; i += 41) {
            std::array<TexPoint, 4> q;
            const double cx[4] = {0, 1, 1, 0}, cy[4] = {0, 0, 1, 1};
            bool ok = true;
            for (int c = 0; c < 4; ++c)
              ok = ok && GroundPoint(view, i + cx[c], j + cy[c], &q[c].x, &q[c].z);
            if (ok) integrator.Color(q, sat, &stats);
          }
      }
      std::mt19937 rng(17);
      std::uniform_real_distribution<double> u(-1, 1), len(1e-4, 0.1), angle(0, M_PI);
      for (int n = 0; n < 2000; ++n) {
        const double a = angle(rng), b = angle(rng), la = len(rng), lb = len(rng);
        const TexPoint o{u(rng), u(rng)};
        const TexPoint e{la * std::cos(a), la * std::sin(a)}, f{lb * std::cos(b), lb * std::sin(b)};
        if (std::abs(e.x * f.z - e.z * f.x) < 1e-3 * la * lb) continue;
        integrator.Color({{o,
                           {o.x + e.x, o.z + e.z},
                           {o.x + e.x + f.x, o.z + e.z + f.z},
                           {o.x + f.x, o.z + f.z}}},
                         sat, &stats);
      }
      EXPECT_GT(stats.quads, 2000);
      EXPECT_LE(stats.MeanRelativeError(), delta) << "delta " << delta;
      EXPECT_GT(stats.MeanRelativeError(), 0.05 * delta) << "delta " << delta;  // not trivially 0
      std::printf(
          "%s, delta %.2f: mean S_fragments / S_quad - 1 = %.4f over %.0f quads, %.1f fragments\n",
          rule == FragmentLevelRule::kPerAxisBound ? "per-axis" : "eq. 9", delta,
          stats.MeanRelativeError(), stats.quads, stats.fragments / stats.quads);
    }
}

}  // namespace
}  // namespace aperture
