// The exact integral over polygons (Green's theorem over the summed-area table's line integrals)
// against an independent exact integral: the polygon clipped to every cell between texel centres,
// where the bilinear texture is c0 + c1 s + c2 t + c3 s t, integrated from the clipped piece's own
// area and moments (vertex formulas). Also against the table's rectangles, a texture that is one
// bilinear polynomial (analytic), and seed 003's fragments converging on it.
#include "trace/polygon_integral.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "testing/random_image.h"
#include "texture/mip_pyramid.h"
#include "texture/summed_area_levels.h"
#include "trace/projection_integral.h"

namespace aperture {
namespace {

using Poly = std::vector<TexPoint>;

Poly Clip(const Poly& in, bool along_x, double value, bool keep_below) {
  Poly out;
  auto key = [&](const TexPoint& p) { return along_x ? p.x : p.z; };
  auto inside = [&](const TexPoint& p) { return keep_below ? key(p) <= value : key(p) >= value; };
  for (size_t k = 0; k < in.size(); ++k) {
    const TexPoint &p = in[k], &q = in[(k + 1) % in.size()];
    if (inside(p)) out.push_back(p);
    if (inside(p) != inside(q)) {
      const double t = (value - key(p)) / (key(q) - key(p));
      out.push_back({p.x + t * (q.x - p.x), p.z + t * (q.z - p.z)});
    }
  }
  return out;
}

// Area, first moments and the moment of x z of a polygon (signed, counterclockwise positive).
struct Moments {
  double a = 0, x = 0, z = 0, xz = 0;
};
Moments PolygonMoments(const Poly& p) {
  Moments m;
  for (size_t k = 0; k < p.size(); ++k) {
    const TexPoint &a = p[k], &b = p[(k + 1) % p.size()];
    const double c = a.x * b.z - b.x * a.z;
    m.a += c / 2;
    m.x += (a.x + b.x) * c / 6;
    m.z += (a.z + b.z) * c / 6;
    m.xz += c * (a.x * b.z + 2 * a.x * a.z + 2 * b.x * b.z + b.x * a.z) / 24;
  }
  return m;
}

// The independent reference: texel units, any position (the texture repeats).
double CellByCellIntegral(const Image& img, int channel, const Poly& poly) {
  const int w = img.width(), h = img.height();
  double u0 = INFINITY, u1 = -INFINITY, w0 = INFINITY, w1 = -INFINITY;
  Poly shifted;
  for (const TexPoint& p : poly) {
    shifted.push_back({p.x - 0.5, p.z - 0.5});
    u0 = std::min(u0, p.x - 0.5), u1 = std::max(u1, p.x - 0.5);
    w0 = std::min(w0, p.z - 0.5), w1 = std::max(w1, p.z - 0.5);
  }
  auto texel = [&](long i, long j) {
    const Rgba& t =
        img.at(static_cast<int>(((i % w) + w) % w), static_cast<int>(((j % h) + h) % h));
    const float v[4] = {t.r, t.g, t.b, t.a};
    return static_cast<double>(v[channel]);
  };
  double sum = 0;
  for (long j = static_cast<long>(std::floor(w0)); j <= static_cast<long>(std::floor(w1)); ++j)
    for (long i = static_cast<long>(std::floor(u0)); i <= static_cast<long>(std::floor(u1)); ++i) {
      Poly cell =
          Clip(Clip(Clip(Clip(shifted, true, i, false), true, i + 1, true), false, j, false), false,
               j + 1, true);
      if (cell.size() < 3) continue;
      for (TexPoint& p : cell) p.x -= i, p.z -= j;
      const Moments m = PolygonMoments(cell);
      const double t00 = texel(i, j), t10 = texel(i + 1, j), t01 = texel(i, j + 1),
                   t11 = texel(i + 1, j + 1);
      sum += t00 * m.a + (t10 - t00) * m.x + (t01 - t00) * m.z + (t11 - t10 - t01 + t00) * m.xz;
    }
  return sum;
}

// A random convex quad: a parallelogram's corners moved by a perspective-like taper.
std::array<TexPoint, 4> RandomQuad(std::mt19937& rng, double cx, double cz, double max_len) {
  std::uniform_real_distribution<double> angle(0, 2 * M_PI), len(0.05, 1.0), taper(0.6, 1.0);
  while (true) {
    const double a = angle(rng), b = angle(rng), la = len(rng) * max_len, lb = len(rng) * max_len;
    const TexPoint e{la * std::cos(a), la * std::sin(a)}, f{lb * std::cos(b), lb * std::sin(b)};
    if (std::abs(e.x * f.z - e.z * f.x) < 0.05 * la * lb) continue;
    const double k = taper(rng);
    return {{{cx - e.x - f.x, cz - e.z - f.z},
             {cx + e.x - f.x, cz + e.z - f.z},
             {cx + k * (e.x + f.x), cz + k * (e.z + f.z)},
             {cx + k * (f.x - e.x), cz + k * (f.z - e.z)}}};
  }
}

TEST(PolygonIntegral, RandomQuadsMatchTheCellByCellIntegral) {
  // Quads from a fraction of a texel to 60 texels across at every angle, so that edges take
  // both forms, cross up to two cells in a band (Gauss-Legendre) or many (the line moments).
  const Image img = RandomImage(37, 23, 5, true);
  const SummedAreaTable table(img, 4);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> x(1, 36), z(1, 22), size(0.02, 1);
  int checked = 0;
  double worst = 0;
  for (int n = 0; n < 400; ++n) {
    const double s = std::pow(size(rng), 2) * 12;
    const auto q = RandomQuad(rng, x(rng), z(rng), s);
    Poly poly(q.begin(), q.end());
    bool inside = true;
    for (const TexPoint& p : q) inside = inside && p.x >= 0 && p.x <= 37 && p.z >= 0 && p.z <= 23;
    if (!inside) continue;
    const auto got = PolygonIntegral(table, poly.data(), 4);
    for (int c = 0; c < 4; ++c) {
      const double want = CellByCellIntegral(img, c, poly);
      const double area = std::abs(PolygonMoments(poly).a);
      EXPECT_NEAR(got[c], want, 1e-9 * std::max(1.0, area)) << "quad " << n << " channel " << c;
      worst = std::max(worst, std::abs(got[c] - want) / area);
    }
    ++checked;
  }
  EXPECT_GT(checked, 200);
  std::printf("%d quads, worst error / area %.3g\n", checked, worst);
}

TEST(PolygonIntegral, RectanglesMatchTheTable) {
  const Image img = RandomImage(16, 16, 3, true);
  const SummedAreaTable table(img, 3);
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> v(0, 16);
  for (int n = 0; n < 200; ++n) {
    double x0 = v(rng), x1 = v(rng), y0 = v(rng), y1 = v(rng);
    if (x0 > x1) std::swap(x0, x1);
    if (y0 > y1) std::swap(y0, y1);
    const TexPoint r[4] = {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
    const auto got = PolygonIntegral(table, r, 4);
    const auto want = table.Integrate(x0, y0, x1, y1);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], want[c], 1e-9) << n;
  }
}

TEST(PolygonIntegral, ABilinearPolynomialTextureIsIntegratedAnalytically) {
  // Texels on p(u, w) = 0.1 + 0.002 u + 0.003 w + 0.0001 u w (u, w from texel centres): the
  // reconstruction is p itself away from the wrapped border, so the integral is p's moments. A
  // wide texture, so that the line moments grow large and their precision is tested too.
  const int w = 4096, h = 64;
  Image img(w, h);
  auto p = [](double u, double v) { return 0.1 + 0.002 * u + 0.003 * v + 0.0001 * u * v; };
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) img.at(i, j) = {static_cast<float>(p(i, j)), 0, 0, 1};
  const SummedAreaTable table(img, 1);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> x(3000, 4000), z(10, 50), size(0.01, 1);
  double worst = 0;
  for (int n = 0; n < 300; ++n) {
    const auto q = RandomQuad(rng, x(rng), z(rng), std::pow(size(rng), 2) * 8);
    Poly shifted;
    for (const TexPoint& t : q) shifted.push_back({t.x - 0.5, t.z - 0.5});
    const Moments m = PolygonMoments(shifted);
    // The texels hold p rounded to float (about 1e-7 relative); the line moments along a row of
    // 4,096 texels reach 1e12 here, so their differences keep about 1e-4 absolute, which the
    // bound of 5e-5 of the mean allows on quads down to 1e-4 texel^2 (PolygonMean takes tables
    // up to 4,096 wide).
    const double want = 0.1 * m.a + 0.002 * m.x + 0.003 * m.z + 0.0001 * m.xz;
    const auto got = PolygonIntegral(table, q.data(), 4);
    EXPECT_NEAR(got[0] / m.a, want / m.a, 5e-5 * std::abs(want / m.a)) << "quad " << n;
    worst = std::max(worst, std::abs(got[0] / want - 1));
  }
  std::printf("worst relative error of the mean %.3g\n", worst);
}

TEST(PolygonIntegral, MeanOverPeriodsMatchesTheCellByCellIntegral) {
  // Quads across the period borders (texture repeats), in repeat units as the tracer gives them.
  const Image img = RandomImage(8, 6, 9, true);
  const SummedAreaTable table(img, 3);
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> c(-3, 3), size(0.05, 1);
  int exact = 0;
  for (int n = 0; n < 300; ++n) {
    const auto q = RandomQuad(rng, c(rng), c(rng), size(rng) * 1.2);
    std::array<double, 4> mean;
    int steps = 0;
    if (!PolygonMean(q, table, 1 << 20, &mean, &steps)) continue;
    ++exact;
    Poly texels;
    for (const TexPoint& p : q) texels.push_back({p.x * 8, p.z * 6});
    const double area = PolygonMoments(texels).a;
    for (int ch = 0; ch < 3; ++ch)
      EXPECT_NEAR(mean[ch], CellByCellIntegral(img, ch, texels) / area, 1e-9) << n;
    EXPECT_GE(steps, 4);
  }
  EXPECT_EQ(exact, 300);
}

TEST(PolygonIntegral, LongQuadsOverManyPeriodsMatchTheCellByCellIntegral) {
  // Pixels near the horizon: thin quads many periods long, at any angle, far from the origin.
  const Image img = RandomImage(8, 6, 13, true);
  const SummedAreaTable table(img, 3);
  std::mt19937 rng(21);
  std::uniform_real_distribution<double> angle(0, 2 * M_PI), len(2, 20), thin(0.01, 0.3),
      c(-100, 100);
  for (int n = 0; n < 100; ++n) {
    const double a = angle(rng), l = len(rng), t = thin(rng), cx = c(rng), cz = c(rng);
    const TexPoint e{l * std::cos(a), l * std::sin(a)}, f{-t * std::sin(a), t * std::cos(a)};
    const std::array<TexPoint, 4> q{{{cx, cz},
                                     {cx + e.x, cz + e.z},
                                     {cx + e.x + 1.3 * f.x, cz + e.z + 1.3 * f.z},
                                     {cx + f.x, cz + f.z}}};
    std::array<double, 4> mean;
    ASSERT_TRUE(PolygonMean(q, table, 1 << 20, &mean)) << n;
    Poly texels;
    const double sx = std::floor(std::min({q[0].x, q[1].x, q[2].x, q[3].x})),
                 sz = std::floor(std::min({q[0].z, q[1].z, q[2].z, q[3].z}));
    for (const TexPoint& p : q) texels.push_back({(p.x - sx) * 8, (p.z - sz) * 6});
    const double area = PolygonMoments(texels).a;
    for (int ch = 0; ch < 3; ++ch)
      EXPECT_NEAR(mean[ch], CellByCellIntegral(img, ch, texels) / area, 1e-9) << n;
  }
}

TEST(PolygonIntegral, RefusesWhatItCannotTakeExactly) {
  const Image img = RandomImage(8, 8, 1, true);
  const SummedAreaTable table(img, 3);
  std::array<double, 4> mean{-1, -1, -1, -1};
  int steps = 0;
  // A bow tie, a quad without area, one over 4,096 unit textures, one over the budget.
  EXPECT_FALSE(PolygonMean({{{0.1, 0.1}, {0.4, 0.4}, {0.4, 0.1}, {0.1, 0.4}}}, table, 100, &mean));
  EXPECT_FALSE(PolygonMean({{{0.1, 0.1}, {0.2, 0.2}, {0.3, 0.3}, {0.4, 0.4}}}, table, 100, &mean));
  EXPECT_FALSE(
      PolygonMean({{{0.1, 0.1}, {5000, 0.1}, {5000, 0.2}, {0.1, 0.2}}}, table, 1000, &mean));
  // Not numbers: a corner ray that went wrong.
  EXPECT_FALSE(PolygonMean({{{0.1, 0.1}, {NAN, 0.2}, {0.4, 0.4}, {0.1, 0.4}}}, table, 100, &mean));
  EXPECT_FALSE(
      PolygonMean({{{0.1, 0.1}, {INFINITY, 0.2}, {0.4, 0.4}, {0.1, 0.4}}}, table, 100, &mean));
  const std::array<TexPoint, 4> diagonal{{{0.1, 0.1}, {0.9, 0.8}, {0.85, 0.9}, {0.05, 0.2}}};
  EXPECT_FALSE(PolygonMean(diagonal, table, 5, &mean, &steps));
  EXPECT_GT(steps, 5);
  EXPECT_EQ(mean[0], -1);  // untouched
  EXPECT_TRUE(PolygonMean(diagonal, table, steps, &mean));
}

TEST(PolygonIntegral, FragmentsConvergeOnTheExactMean) {
  // Seed 003's fragments (exact path off) approach the exact mean as delta falls.
  const Image img = RandomImage(64, 64, 8, true);
  const SummedAreaTable table(img, 3);
  const std::array<TexPoint, 4> q{{{0.31, 0.22}, {0.52, 0.27}, {0.50, 0.61}, {0.28, 0.48}}};
  std::array<double, 4> exact;
  ASSERT_TRUE(PolygonMean(q, table, 1 << 20, &exact));
  double last = INFINITY;
  for (double delta : {0.1, 0.01, 0.001}) {
    FragmentOptions opt;
    opt.delta = delta;
    opt.exact_steps = 0;
    opt.max_cells = 1 << 16;
    ProjectionIntegrator integrator(opt);
    const double err = std::abs(integrator.Color(q, table).r - exact[0]);
    std::printf("delta %g: |fragments - exact| = %.3g\n", delta, err);
    EXPECT_LT(err, 0.2 * delta);
    last = err;
  }
  EXPECT_LT(last, 1e-4);
  // And the integrator takes the exact path by default.
  ProjectionIntegrator integrator{FragmentOptions{}};
  FragmentStats stats;
  EXPECT_NEAR(integrator.Color(q, table, &stats).r, exact[0], 1e-6);
  EXPECT_EQ(stats.exact, 1);
  EXPECT_EQ(stats.quads, 0);
}

TEST(PolygonIntegral, ProjectionsTheFragmentsCannotBoundTakeACoarserLevel) {
  // Next to the horizon: a projection 0.3 repeats wide and 1,700 long, slanted. Its fragments hit
  // the work cap (1,024 columns) and miss delta; it takes the texture's mean (no level's steps
  // fit), which over 2,000 periods is its true mean within a small fraction of the contrast. A
  // shorter slanted sliver over 12 periods takes a coarser level, near the exact base integral.
  const Image img = RandomImage(64, 64, 17, true);
  const MipPyramid pyramid(img);
  const auto tables = BuildSummedAreaLevels(pyramid, 3);
  std::vector<const SummedAreaTable*> levels;
  for (const auto& t : tables) levels.push_back(t.get());
  const TableIntegral texture(levels);
  ProjectionIntegrator integrator{FragmentOptions{}};

  FragmentStats stats;
  const std::array<TexPoint, 4> horizon{
      {{0.22, 0.99}, {0.71, 0.99}, {1315.81, 1719.23}, {1315.64, 1719.23}}};
  const Rgba far = integrator.Color(horizon, texture, &stats);
  EXPECT_EQ(stats.coarse, 1);
  double mean[3] = {};
  for (const Rgba& t : img.texels()) mean[0] += t.r, mean[1] += t.g, mean[2] += t.b;
  EXPECT_NEAR(far.r, mean[0] / img.texels().size(), 1e-6);
  EXPECT_NEAR(far.b, mean[2] / img.texels().size(), 1e-6);

  stats = {};
  const std::array<TexPoint, 4> sliver{{{0.1, 0.1}, {0.104, 0.1}, {9.3, 7.9}, {9.296, 7.9}}};
  const Rgba got = integrator.Color(sliver, texture, &stats);
  std::array<double, 4> exact;
  ASSERT_TRUE(PolygonMean(sliver, *levels[0], 1 << 20, &exact));
  std::printf("sliver: coarse %.0f (level %.0f), %.4f against the exact %.4f\n", stats.coarse,
              stats.coarse_level_sum, got.r, exact[0]);
  EXPECT_EQ(stats.coarse, 1);
  EXPECT_GE(stats.coarse_level_sum, 1);
  EXPECT_NEAR(got.r, exact[0], 0.02);

  // With exact integrals off, seed 003's fragments take both, as the paper does.
  FragmentOptions paper;
  paper.exact_steps = 0;
  ProjectionIntegrator fragments(paper);
  stats = {};
  fragments.Color(sliver, texture, &stats);
  EXPECT_EQ(stats.coarse, 0);
  EXPECT_EQ(stats.quads, 1);
}

}  // namespace
}  // namespace aperture
