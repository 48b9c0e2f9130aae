// Summed-area tables against brute-force integrals of the bilinear texture: the rectangle is cut
// at every texel centre (where the reconstruction's pieces meet) and each bilinear piece is
// integrated exactly by 2 x 2 Gauss-Legendre points.
#include "texture/summed_area_table.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace aperture {
namespace {

Image RandomTexture(int w, int h, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> byte(0, 255);
  Image img(w, h);
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i)
      img.at(i, j) = {byte(rng) / 255.0f, byte(rng) / 255.0f, byte(rng) / 255.0f,
                      byte(rng) / 255.0f};
  return img;
}

// The periodic bilinear reconstruction at (x, y) in texel units, in double.
double Bilinear(const Image& img, int channel, double x, double y) {
  const int w = img.width(), h = img.height();
  const double xs = x - 0.5, ys = y - 0.5, fx = xs - std::floor(xs), fy = ys - std::floor(ys);
  auto wrap = [](long i, int n) { return static_cast<int>(((i % n) + n) % n); };
  const long i0 = static_cast<long>(std::floor(xs)), j0 = static_cast<long>(std::floor(ys));
  auto t = [&](long i, long j) {
    const Rgba& p = img.at(wrap(i, w), wrap(j, h));
    const float v[4] = {p.r, p.g, p.b, p.a};
    return static_cast<double>(v[channel]);
  };
  return (t(i0, j0) * (1 - fx) + t(i0 + 1, j0) * fx) * (1 - fy) +
         (t(i0, j0 + 1) * (1 - fx) + t(i0 + 1, j0 + 1) * fx) * fy;
}

// Cut points of [lo, hi] at texel centres.
std::vector<double> Cuts(double lo, double hi) {
  std::vector<double> c{lo};
  for (double k = std::floor(lo - 0.5) + 1.5; k < hi; k += 1)
    if (k > lo) c.push_back(k);
  c.push_back(hi);
  return c;
}

double BruteIntegral(const Image& img, int channel, double x0, double y0, double x1, double y1) {
  const double g = 0.5 / std::sqrt(3.0);
  const auto cx = Cuts(x0, x1), cy = Cuts(y0, y1);
  double sum = 0;
  for (size_t a = 0; a + 1 < cx.size(); ++a)
    for (size_t b = 0; b + 1 < cy.size(); ++b) {
      const double mx = 0.5 * (cx[a] + cx[a + 1]), hx = cx[a + 1] - cx[a];
      const double my = 0.5 * (cy[b] + cy[b + 1]), hy = cy[b + 1] - cy[b];
      double piece = 0;
      for (double sx : {-g, g})
        for (double sy : {-g, g}) piece += Bilinear(img, channel, mx + sx * hx, my + sy * hy);
      sum += 0.25 * piece * hx * hy;
    }
  return sum;
}

TEST(SummedAreaTable, RandomRectanglesWithFractionalEdgesMatchBruteForce) {
  const Image img = RandomTexture(37, 29, 1);
  const SummedAreaTable sat(img, 4);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> ux(0, 37), uy(0, 29);
  for (int n = 0; n < 300; ++n) {
    double x0 = ux(rng), x1 = ux(rng), y0 = uy(rng), y1 = uy(rng);
    if (x0 > x1) std::swap(x0, x1);
    if (y0 > y1) std::swap(y0, y1);
    const auto got = sat.Integrate(x0, y0, x1, y1);
    for (int c = 0; c < 4; ++c)
      ASSERT_NEAR(got[c], BruteIntegral(img, c, x0, y0, x1, y1), 1e-10)
          << x0 << "," << y0 << " - " << x1 << "," << y1 << " channel " << c;
  }
}

TEST(SummedAreaTable, TinyAndOneTexelRectangles) {
  const Image img = RandomTexture(16, 16, 2);
  const SummedAreaTable sat(img, 3);
  // One texel, aligned: the bilinear texture over [i, i + 1] x [j, j + 1].
  for (int j : {0, 5, 15})
    for (int i : {0, 7, 15}) {
      const auto got = sat.Integrate(i, j, i + 1, j + 1);
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(got[c], BruteIntegral(img, c, i, j, i + 1, j + 1), 1e-12);
    }
  // A 1e-3 square equals the texture's value there times its area.
  const double x = 3.3, y = 9.71, e = 1e-3;
  const auto got = sat.Integrate(x, y, x + e, y + e);
  EXPECT_NEAR(got[1] / (e * e), Bilinear(img, 1, x + e / 2, y + e / 2), 1e-6);
  // Alpha is not tabulated with 3 channels.
  EXPECT_EQ(got[3], 0.0);
  // Empty and inverted rectangles integrate to 0.
  EXPECT_EQ(sat.Integrate(4, 4, 4, 9)[0], 0.0);
  EXPECT_EQ(sat.Integrate(5, 4, 4, 9)[0], 0.0);
}

TEST(SummedAreaTable, WholeTextureIsTheSumOfTexels) {
  // The periodic bilinear reconstruction integrates to the sum of its samples over one period,
  // and so does every shift of the period (checked by the wrapping integral).
  const Image img = RandomTexture(20, 12, 3);
  const SummedAreaTable sat(img, 4);
  double sum[4] = {};
  for (const Rgba& t : img.texels()) sum[0] += t.r, sum[1] += t.g, sum[2] += t.b, sum[3] += t.a;
  const auto whole = sat.Integrate(0, 0, 20, 12);
  const auto shifted = sat.IntegratePeriodic(-7.25, 3.5, 12.75, 15.5);
  for (int c = 0; c < 4; ++c) {
    EXPECT_NEAR(whole[c], sum[c], 1e-10);
    EXPECT_NEAR(shifted[c], sum[c], 1e-10);
  }
}

TEST(SummedAreaTable, WrappingRectanglesMatchBruteForce) {
  const Image img = RandomTexture(32, 16, 4);
  const SummedAreaTable sat(img, 1);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> pos(-100, 100), len(0, 70);
  for (int n = 0; n < 100; ++n) {
    const double x0 = pos(rng), y0 = pos(rng), x1 = x0 + len(rng), y1 = y0 + len(rng) * 0.5;
    EXPECT_NEAR(sat.IntegratePeriodic(x0, y0, x1, y1)[0], BruteIntegral(img, 0, x0, y0, x1, y1),
                1e-8)
        << x0 << "," << y0 << " - " << x1 << "," << y1;
  }
  // Across the border between the last and first texel: the reconstruction wraps there.
  EXPECT_NEAR(sat.IntegratePeriodic(31.6, 15.2, 32.4, 16.9)[0],
              BruteIntegral(img, 0, 31.6, 15.2, 32.4, 16.9), 1e-12);
}

TEST(SummedAreaTable, LargeTextureKeepsPrecision) {
  // 4096 x 4096: the tables reach ~1.7e7, yet a small rectangle at the far corner is exact to
  // float rounding of its own size.
  const int n = 4096;
  Image img(n, n);
  std::mt19937 rng(5);
  std::uniform_int_distribution<int> byte(0, 255);
  for (Rgba& t : img.texels()) t.r = byte(rng) / 255.0f;
  const SummedAreaTable sat(img, 1);
  std::uniform_real_distribution<double> far(4000, 4090), len(0.001, 5);
  for (int k = 0; k < 200; ++k) {
    const double x0 = far(rng), y0 = far(rng), x1 = x0 + len(rng), y1 = y0 + len(rng);
    const double brute = BruteIntegral(img, 0, x0, y0, x1, y1);
    const double area = (x1 - x0) * (y1 - y0);
    EXPECT_NEAR(sat.Integrate(x0, y0, x1, y1)[0] / area, brute / area, 1e-6)
        << x0 << "," << y0 << " - " << x1 << "," << y1;
  }
  long double total = 0;
  for (const Rgba& t : img.texels()) total += t.r;
  EXPECT_NEAR(sat.Integrate(0, 0, n, n)[0], static_cast<double>(total), 1e-6);
}

}  // namespace
}  // namespace aperture

namespace aperture {
namespace {

// The fast paths: rectangles within one cell between texel centres, thin columns within one cell
// column spanning many rows, thin rows likewise, including cells at the texture's borders; and
// the general path next to them (columns and rows straddling one texel centre).
TEST(SummedAreaTable, InCellColumnAndRowRectanglesMatchBruteForce) {
  const Image img = RandomTexture(32, 16, 11);
  const SummedAreaTable sat(img, 4);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u01(0, 1);
  double worst = 0;
  for (int k = 0; k < 600; ++k) {
    // A cell [c, c + 1] between texel centres, c = i + 0.5 for i in -1 .. n - 1 (clipped to the
    // texture), and a random sub-interval of it; the other axis in-cell, thin or long.
    auto in_cell = [&](int n, double* lo, double* hi) {
      const double c = std::floor(u01(rng) * (n + 1)) - 0.5;
      double a = c + u01(rng), b = c + u01(rng);
      if (a > b) std::swap(a, b);
      *lo = std::clamp(a, 0.0, double(n)), *hi = std::clamp(b, 0.0, double(n));
    };
    auto two_cells = [&](int n, double* lo, double* hi) {  // straddling one texel centre
      const double c = std::floor(u01(rng) * n) - 0.5;
      *lo = std::clamp(c + u01(rng), 0.0, double(n));
      *hi = std::clamp(c + 1 + u01(rng), *lo, double(n));
    };
    auto any = [&](int n, double* lo, double* hi) {
      double a = u01(rng) * n, b = u01(rng) * n;
      if (a > b) std::swap(a, b);
      *lo = a, *hi = b;
    };
    double x0, x1, y0, y1;
    switch (k % 5) {
      case 0:
        in_cell(32, &x0, &x1), in_cell(16, &y0, &y1);
        break;
      case 1:
        in_cell(32, &x0, &x1), any(16, &y0, &y1);
        break;
      case 2:
        any(32, &x0, &x1), in_cell(16, &y0, &y1);
        break;
      case 3:
        two_cells(32, &x0, &x1), any(16, &y0, &y1);
        break;
      default:
        any(32, &x0, &x1), two_cells(16, &y0, &y1);
        break;
    }
    const auto got = sat.Integrate(x0, y0, x1, y1);
    for (int c = 0; c < 4; ++c)
      worst = std::max(worst, std::abs(got[c] - BruteIntegral(img, c, x0, y0, x1, y1)));
  }
  EXPECT_LT(worst, 1e-10);
}

}  // namespace
}  // namespace aperture
