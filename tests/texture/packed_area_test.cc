#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>
#include <vector>

#include "texture/packed/area_integral.h"
#include "texture/packed/packed_sampler.h"
#include "texture/packed_test_images.h"

namespace aperture::packed {
namespace {

using testing::RandomIndexedImage;

// Weight of texel [i, i + 1) under the periodic interval [a, b): the overlap of [a, b) with all
// copies [i + k n, i + 1 + k n).
double Coverage(double a, double b, uint32_t i, uint32_t n) {
  double w = 0;
  const double k0 = std::floor((a - i - 1) / n), k1 = std::ceil((b - i) / n);
  for (double k = k0; k <= k1; ++k) {
    const double lo = std::max(a, i + k * n), hi = std::min(b, i + 1 + k * n);
    if (hi > lo) w += hi - lo;
  }
  return w;
}

AreaSum BruteForce(const IndexedImage& image, double x0, double y0, double x1, double y1) {
  AreaSum s;
  s.area = (x1 - x0) * (y1 - y0);
  for (uint32_t y = 0; y < image.height; ++y) {
    const double wy = Coverage(y0, y1, y, image.height);
    if (wy == 0) continue;
    for (uint32_t x = 0; x < image.width; ++x) {
      const double w = wy * Coverage(x0, x1, x, image.width);
      const uint32_t colour = image.palette[image.at(x, y)];
      for (int c = 0; c < 4; ++c) s.channels[c] += w * Channel(colour, c);
    }
  }
  return s;
}

void ExpectNear(const AreaSum& got, const AreaSum& want, const char* what) {
  for (int c = 0; c < 4; ++c)
    ASSERT_NEAR(got.channels[c], want.channels[c],
                1e-9 * std::max(1.0, std::fabs(want.channels[c])))
        << what << " channel " << c;
  ASSERT_NEAR(got.area, want.area, 1e-9 * std::max(1.0, want.area)) << what;
}

TEST(PackedArea, IntegralsEqualBruteForceSums) {
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> unit(0, 1);
  for (Curve curve : {Curve::kHilbert, Curve::kMorton}) {
    for (auto [w, h] : {std::pair{1u, 1u}, {1u, 50u}, {37u, 23u}, {64u, 64u}, {100u, 33u}}) {
      for (bool blocky : {false, true}) {
        const IndexedImage image =
            RandomIndexedImage(w, h, blocky ? 6 : 200, w * h + blocky, blocky);
        auto packed = PackTexture(image, curve);
        ASSERT_TRUE(packed.ok());
        // Every run searched, and with the run index (cells of one colour summed from the index,
        // the others descended into).
        const RunIndex index(packed->view());
        const AreaIntegrator plain(packed->view()), indexed(packed->view(), &index);
        for (const AreaIntegrator* integrator : {&plain, &indexed}) {
          const AreaIntegrator& area = *integrator;
          // Whole texture, one texel, random rectangles inside, wrapping, and over many periods.
          ExpectNear(area.Integrate(0, 0, w, h), BruteForce(image, 0, 0, w, h), "whole");
          for (int i = 0; i < 40; ++i) {
            const uint32_t x = rng() % w, y = rng() % h;
            ExpectNear(area.Integrate(x, y, x + 1, y + 1), BruteForce(image, x, y, x + 1, y + 1),
                       "one texel");
            double x0 = unit(rng) * w, y0 = unit(rng) * h;
            double x1 = x0 + unit(rng) * (w - x0), y1 = y0 + unit(rng) * (h - y0);
            ExpectNear(area.Integrate(x0, y0, x1, y1), BruteForce(image, x0, y0, x1, y1), "inside");
            x0 = (unit(rng) - 0.5) * 4 * w;
            y0 = (unit(rng) - 0.5) * 4 * h;
            x1 = x0 + unit(rng) * 2.5 * w;
            y1 = y0 + unit(rng) * 2.5 * h;
            ExpectNear(area.Integrate(x0, y0, x1, y1), BruteForce(image, x0, y0, x1, y1),
                       "wrapping");
            x0 = unit(rng) * 0.9;  // inside one texel
            y0 = unit(rng) * 0.9;
            ExpectNear(area.Integrate(x0, y0, x0 + 0.1, y0 + 0.05),
                       BruteForce(image, x0, y0, x0 + 0.1, y0 + 0.05), "sub-texel");
          }
        }
      }
    }
  }
}

// With the run index, a cell (or subcell) of one colour adds colour x overlap at once and a
// descent's first block searches its runs inside its cell's (or subcell's) range: the integrals
// must be those of every run searched (to double rounding: the index adds the same terms in
// another order), on textures whose cells have one run, several, or detail records, square or
// not, with both curves.
TEST(PackedArea, TheRunIndexNarrowsTheSearchWithoutChangingAnIntegral) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> unit(0, 1);
  int narrowed_sizes = 0;
  for (Curve curve : {Curve::kHilbert, Curve::kMorton}) {
    for (auto [w, h] : {std::pair{512u, 512u}, {700u, 300u}, {256u, 1000u}}) {
      for (bool blocky : {false, true}) {
        const IndexedImage image =
            RandomIndexedImage(w, h, blocky ? 9 : 200, w + h + blocky, blocky);
        auto packed = PackTexture(image, curve);
        ASSERT_TRUE(packed.ok());
        const RunIndex index(packed->view());
        const AreaIntegrator plain(packed->view()), indexed(packed->view(), &index);
        for (int i = 0; i < 3000; ++i) {
          // Rectangles of 0.1 to 40 texels, so that first blocks fall within cells, within
          // subcells, and across them; some wrap.
          const double size = std::exp(unit(rng) * std::log(400.0)) * 0.1;
          const double x0 = unit(rng) * w * 1.02, y0 = unit(rng) * h * 1.02;
          const double x1 = x0 + size * (0.2 + unit(rng)), y1 = y0 + size * (0.2 + unit(rng));
          const AreaSum a = plain.Integrate(x0, y0, x1, y1), b = indexed.Integrate(x0, y0, x1, y1);
          for (int c = 0; c < 4; ++c)
            ASSERT_NEAR(a.channels[c], b.channels[c], 1e-12 * std::max(1.0, a.channels[c])) << i;
          ASSERT_EQ(a.area, b.area);
          uint32_t lo, hi;
          narrowed_sizes += index.RunsAround(static_cast<uint32_t>(x0) % w,
                                             static_cast<uint32_t>(y0) % h, 0, lo, hi);
        }
      }
    }
  }
  EXPECT_GT(narrowed_sizes, 10000);  // the index answered for most single texels
}

// A thread keeps the runs of the blocks its integrals visited, per integrator. Integrators made
// and dropped one after another (likely at the same address) over different textures of one size
// must never answer from another's entries: each integral equals the brute-force sum of its own
// texture, and a second pass over the same rectangles (answered from the cache) gives the same
// values bit for bit as the first.
TEST(PackedArea, AThreadsCachedBlockRunsNeverAnswerForAnotherTexture) {
  std::mt19937_64 rng(23);
  std::uniform_real_distribution<double> unit(0, 1);
  std::vector<std::array<double, 4>> rects;
  for (int i = 0; i < 60; ++i) {
    const double x0 = unit(rng) * 64, y0 = unit(rng) * 64;
    rects.push_back({x0, y0, x0 + 0.5 + unit(rng) * 20, y0 + 0.5 + unit(rng) * 20});
  }
  for (int texture = 0; texture < 12; ++texture) {
    const IndexedImage image =
        RandomIndexedImage(64, 64, texture % 2 ? 5 : 120, 100 + texture, texture % 2 == 1);
    auto packed = PackTexture(image, texture % 3 ? Curve::kHilbert : Curve::kMorton);
    ASSERT_TRUE(packed.ok());
    const RunIndex index(packed->view());
    const AreaIntegrator area(packed->view(), &index);
    std::vector<AreaSum> first;
    for (const auto& [x0, y0, x1, y1] : rects) {
      first.push_back(area.Integrate(x0, y0, x1, y1));
      ExpectNear(first.back(), BruteForce(image, x0, y0, x1, y1), "texture");
    }
    for (size_t i = 0; i < rects.size(); ++i) {
      const auto& [x0, y0, x1, y1] = rects[i];
      const AreaSum again = area.Integrate(x0, y0, x1, y1);
      for (int c = 0; c < 4; ++c) ASSERT_EQ(again.channels[c], first[i].channels[c]) << i;
    }
  }
}

TEST(PackedArea, IntegerSumsAreExactOnAMap) {
  const IndexedImage image = RandomIndexedImage(512, 300, 9, 77, true);
  auto packed = PackTexture(image, Curve::kHilbert);
  ASSERT_TRUE(packed.ok());
  const AreaIntegrator area(packed->view());
  std::mt19937 rng(5);
  for (int i = 0; i < 50; ++i) {
    const uint32_t x0 = rng() % 512, y0 = rng() % 300;
    const uint32_t x1 = x0 + rng() % (513 - x0), y1 = y0 + rng() % (301 - y0);
    std::array<uint64_t, 4> want{};
    for (uint32_t y = y0; y < y1; ++y)
      for (uint32_t x = x0; x < x1; ++x)
        for (int c = 0; c < 4; ++c) want[c] += Channel(image.palette[image.at(x, y)], c);
    ASSERT_EQ(area.SumTexels(x0, y0, x1, y1), want);
  }
}

TEST(PackedSampler, NearestAndAreaModes) {
  const IndexedImage image = RandomIndexedImage(20, 10, 4, 3, true);
  auto packed = PackTexture(image, Curve::kHilbert);
  ASSERT_TRUE(packed.ok());
  const PackedTextureSampler nearest(packed->view(), PackedSampling::kNearest);
  const PackedTextureSampler area(packed->view(), PackedSampling::kArea);
  // Texel (i, j) covers [i, i+1) x [j, j+1) in texel units; repeats every unit in (u, v).
  for (uint32_t y = 0; y < 10; ++y) {
    for (uint32_t x = 0; x < 20; ++x) {
      const uint32_t c = image.palette[image.at(x, y)];
      const Rgba want{Channel(c, 0) / 255.0f, Channel(c, 1) / 255.0f, Channel(c, 2) / 255.0f,
                      Channel(c, 3) / 255.0f};
      EXPECT_EQ(nearest.Nearest((x + 0.5) / 20.0 - 3, (y + 0.5) / 10.0 + 1000), want);
      TextureFootprint f;
      f.u = (x + 0.5) / 20.0 + 7;
      f.v = (y + 0.5) / 10.0 - 2;
      EXPECT_EQ(nearest.Sample(f), want);
      f.dudx = 0.5f / 20;  // half a texel wide footprint, inside the texel
      f.dvdy = 0.5f / 10;
      const Rgba a = area.Sample(f);
      EXPECT_NEAR(a.r, want.r, 1e-6);
      EXPECT_NEAR(a.a, want.a, 1e-6);
    }
  }
  // The mean over whole periods is the texture's mean.
  const AreaIntegrator integrator(packed->view());
  const AreaSum whole = integrator.Integrate(0, 0, 20, 10);
  const Rgba mean = area.AreaMean(-2, 5, 1, 8);
  EXPECT_NEAR(mean.g, whole.channels[1] / (255.0 * 200), 1e-6);
}

// Footprints 16 or more texels across have their edges snapped to aligned blocks of at most 1/8
// of their shorter side (the cost bound of far, grazing pixels); smaller ones are exact.
TEST(PackedSampler, LargeFootprintsStayCloseToTheExactMean) {
  const IndexedImage image = RandomIndexedImage(512, 512, 9, 11, true);
  auto packed = PackTexture(image, Curve::kHilbert);
  ASSERT_TRUE(packed.ok());
  const PackedTextureSampler area(packed->view(), PackedSampling::kArea);
  std::mt19937_64 rng(8);
  std::uniform_real_distribution<double> unit(0, 1);
  double sum_error = 0;
  int large = 0;
  for (int i = 0; i < 400; ++i) {
    TextureFootprint f;
    f.u = unit(rng) * 3 - 1;
    f.v = unit(rng) * 3 - 1;
    f.dudx = static_cast<float>(std::exp2(unit(rng) * 8) / 512);  // 1 to 256 texels
    f.dvdy = static_cast<float>(std::exp2(unit(rng) * 8) / 512);
    const double hu = 0.5 * f.dudx, hv = 0.5 * f.dvdy;
    const Rgba exact = area.AreaMean(f.u - hu, f.v - hv, f.u + hu, f.v + hv);
    const Rgba got = area.Sample(f);
    const double shorter = std::min(f.dudx, f.dvdy) * 512.0;
    if (shorter < 16) {
      EXPECT_EQ(got, exact) << "footprint " << shorter << " texels across";
      continue;
    }
    ++large;
    // Each edge moves by at most 1/16 of the shorter side, so at most about a quarter of the
    // rectangle changes.
    for (float d : {got.r - exact.r, got.g - exact.g, got.b - exact.b, got.a - exact.a}) {
      EXPECT_LE(std::fabs(d), 0.27) << "footprint " << shorter << " texels across";
      sum_error += std::fabs(d) / 4;
    }
  }
  ASSERT_GT(large, 50);
  EXPECT_LT(sum_error / large, 0.005) << "mean error over " << large << " large footprints";
}

}  // namespace
}  // namespace aperture::packed
