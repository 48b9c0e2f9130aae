// The grazing-plane benchmark's geometry: analytic footprints against finite differences of the
// projection, the measured rows, the reference on a constant texture, the pooled PSNR of several
// measurements and the camera positions that aperture-bench filter --positions pools.
#include "testing/grazing_plane.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "texture/reference_sampler.h"

namespace aperture {
namespace {

TEST(GrazingPlane, FootprintIsTheApertureScaledDerivativeOfTheProjection) {
  for (double pitch : {5.0, 20.0, 60.0}) {
    GrazingPlaneView view;
    view.pitch_deg = pitch;
    view.aperture = 2;
    for (int j = FirstMeasuredRow(view); j < view.height; j += 97) {
      for (int i = 0; i < view.width; i += 131) {
        TextureFootprint f;
        ASSERT_TRUE(GroundFootprint(view, i, j, &f));
        const double px = i + 0.5, py = j + 0.5, h = 1e-3;
        double u0, v0, u1, v1, u2, v2, u3, v3;
        ASSERT_TRUE(GroundPoint(view, px - h, py, &u0, &v0));
        ASSERT_TRUE(GroundPoint(view, px + h, py, &u1, &v1));
        ASSERT_TRUE(GroundPoint(view, px, py - h, &u2, &v2));
        ASSERT_TRUE(GroundPoint(view, px, py + h, &u3, &v3));
        const double s = view.aperture / (2 * h);
        EXPECT_NEAR(f.dudx, (u1 - u0) * s, 1e-4 * std::abs(f.dudx) + 1e-9);
        EXPECT_NEAR(f.dvdx, (v1 - v0) * s, 1e-9);
        EXPECT_NEAR(f.dudy, (u3 - u2) * s, 1e-4 * std::abs(f.dudy) + 1e-9);
        EXPECT_NEAR(f.dvdy, (v3 - v2) * s, 1e-4 * std::abs(f.dvdy) + 1e-9);
        double u, v;
        ASSERT_TRUE(GroundPoint(view, px, py, &u, &v));
        EXPECT_NEAR(f.u, u - std::floor(u), 1e-9);
        EXPECT_NEAR(f.v, v - std::floor(v), 1e-9);
      }
    }
  }
}

TEST(GrazingPlane, MeasuredRowsStartWhereTheWholeApertureIsBelowTheHorizon) {
  GrazingPlaneView view;
  view.pitch_deg = 60;
  EXPECT_EQ(FirstMeasuredRow(view), 0);  // the horizon is above the image
  view.pitch_deg = 5;
  const int first = FirstMeasuredRow(view);
  // Horizon: 384 - (384 / tan 30) tan 5 = 325.8; the 2 x 2 aperture of row j spans
  // [j - 0.5, j + 1.5].
  EXPECT_EQ(first, 327);
  double u, v;
  EXPECT_TRUE(GroundPoint(view, 10.5, first - 0.5 + 1e-9, &u, &v));
  EXPECT_FALSE(GroundPoint(view, 10.5, first - 1.5, &u, &v));
}

TEST(GrazingPlane, ReferenceOfAConstantTextureIsTheConstant) {
  const Rgba c{0.25f, 0.5f, 0.75f, 1};
  const Image texture(16, 16, c);
  GrazingPlaneView view;
  view.width = 64;
  view.height = 48;
  view.pitch_deg = 5;
  const Image ref = RenderGroundReference(view, texture, 1.0, 16);
  for (int j = FirstMeasuredRow(view); j < view.height; ++j)
    for (int i = 0; i < view.width; ++i) {
      ASSERT_NEAR(ref.at(i, j).r, c.r, 1e-6);
      ASSERT_NEAR(ref.at(i, j).b, c.b, 1e-6);
    }
  EXPECT_TRUE(std::isinf(Psnr(ref, ref, 0)));
}

TEST(GrazingPlane, PooledPsnrIsThePsnrOfTheMeasurementsTogether) {
  // Two pairs of images of equal size, scored apart and as one image stacked from both.
  const int w = 37, h = 11;
  Image a(w, 2 * h), b(w, 2 * h), a0(w, h), b0(w, h), a1(w, h), b1(w, h);
  uint32_t state = 12345;
  auto next = [&state] {
    state = state * 1664525u + 1013904223u;
    return static_cast<float>(state >> 8) / 16777216.0f;
  };
  for (int j = 0; j < 2 * h; ++j)
    for (int i = 0; i < w; ++i) {
      // The second half's errors are ten times the first's: unequal PSNRs.
      const float scale = j < h ? 0.01f : 0.1f;
      const Rgba p{next(), next(), next(), 1};
      const Rgba q{p.r + scale * (next() - 0.5f), p.g + scale * (next() - 0.5f),
                   p.b + scale * (next() - 0.5f), 1};
      a.at(i, j) = p, b.at(i, j) = q;
      (j < h ? a0 : a1).at(i, j % h) = p;
      (j < h ? b0 : b1).at(i, j % h) = q;
    }
  const double apart[] = {Psnr(a0, b0, 0), Psnr(a1, b1, 0)};
  EXPECT_GT(apart[0] - apart[1], 15.0);
  EXPECT_NEAR(PooledPsnr(apart), Psnr(a, b, 0), 1e-9);
  const double one[] = {apart[1]}, exact[] = {INFINITY, INFINITY}, mixed[] = {INFINITY, 20.0};
  EXPECT_DOUBLE_EQ(PooledPsnr(one), apart[1]);
  EXPECT_EQ(PooledPsnr(exact), INFINITY);
  EXPECT_NEAR(PooledPsnr(mixed), 20.0 + 10.0 * std::log10(2.0), 1e-12);  // half the error
}

TEST(GrazingPlane, TheSpreadAcrossYawsIsTheHighestLessTheLowestAtTheLowestsYaw) {
  const double yaws[] = {0, 15, 30, 45, 60, 90};
  const double psnrs[] = {40.85, 40.72, 40.91, 41.09, 40.46, 40.86};
  const YawSpread s = SpreadAcrossYaws(yaws, psnrs);
  EXPECT_NEAR(s.spread, 41.09 - 40.46, 1e-12);
  EXPECT_EQ(s.lowest_yaw, 60);
  // A tie: the first lowest; one view: no spread; unequal or empty spans: nothing to compare.
  const double tied[] = {30, 31, 30, 32, 33, 34};
  EXPECT_EQ(SpreadAcrossYaws(yaws, tied).lowest_yaw, 0);
  EXPECT_EQ(SpreadAcrossYaws(std::span(yaws, 1), std::span(psnrs, 1)).spread, 0);
  EXPECT_TRUE(std::isnan(SpreadAcrossYaws(yaws, std::span(psnrs, 5)).lowest_yaw));
  EXPECT_TRUE(std::isnan(SpreadAcrossYaws({}, {}).lowest_yaw));
}

TEST(GrazingPlane, TheFootprintsAngleFromTheAxesFollowsTheYawAndBandsPoolToTheWholePsnr) {
  // Near the horizon in the middle column, the footprint's long axis runs along the line of
  // sight: at yaw y, y degrees from V, so min(y, 90 - y) from the nearest axis.
  for (double yaw : {0.0, 10.0, 30.0, 45.0, 60.0, 80.0, 90.0}) {
    GrazingPlaneView view;
    view.pitch_deg = 5, view.yaw_deg = yaw;
    const int row = FirstMeasuredRow(view) + 2;
    EXPECT_NEAR(FootprintAngleFromAxis(view, view.width / 2, row), std::min(yaw, 90 - yaw), 0.5)
        << "yaw " << yaw;
  }
  GrazingPlaneView view;
  view.pitch_deg = 5, view.yaw_deg = 30;
  EXPECT_EQ(FootprintAngleFromAxis(view, view.width / 2, 0), 0.0);  // sky
  // Left and right of the middle the line of sight turns the other way: angles both sides of 30.
  const int row = FirstMeasuredRow(view) + 2;
  EXPECT_LT(FootprintAngleFromAxis(view, view.width / 4, row), 30.0);
  EXPECT_GT(FootprintAngleFromAxis(view, 3 * view.width / 4, row), 30.0);

  // PsnrByBand: bands of a measure (here the column) pool back to the whole image's PSNR.
  const int w = 40, h = 8;
  Image a(w, h), b(w, h);
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) {
      a.at(i, j) = {0.5f, 0.5f, 0.5f, 1};
      const float e = 0.001f * static_cast<float>(1 + i % 7);
      b.at(i, j) = {0.5f + e, 0.5f - e, 0.5f, 1};
    }
  std::vector<uint64_t> pixels;
  const std::vector<double> bands = PsnrByBand(
      a, b, 0, [](int i, int) { return static_cast<double>(i); }, {10, 30}, &pixels);
  ASSERT_EQ(bands.size(), 3u);
  EXPECT_EQ(pixels, (std::vector<uint64_t>{10 * h, 20 * h, 10 * h}));
  double mse = 0;
  for (size_t k = 0; k < 3; ++k)
    mse += static_cast<double>(pixels[k]) * std::pow(10.0, -bands[k] / 10);
  EXPECT_NEAR(10 * std::log10(w * h / mse), Psnr(a, b, 0), 1e-9);
}

TEST(GrazingPlane, PositionsMoveTheGroundByTheirOriginsAndSpreadTheTexelPhases) {
  GrazingPlaneView view;
  view.pitch_deg = 5, view.yaw_deg = 30;
  const GrazingPlaneView same = ViewAtPosition(view, 0);
  EXPECT_EQ(same.origin_u, view.origin_u);
  EXPECT_EQ(same.origin_v, view.origin_v);
  // The positions 0..15 along both axes: every quarter of the repeat and every quarter of a
  // texel's phase (1024 texels a repeat) is met at least twice.
  int quarters[2][4] = {}, texel_quarters[2][4] = {};
  for (int k = 0; k < 16; ++k) {
    const GrazingPlaneView at = ViewAtPosition(view, k);
    EXPECT_EQ(at.pitch_deg, view.pitch_deg);
    EXPECT_EQ(at.yaw_deg, view.yaw_deg);
    double u0, v0, u1, v1;
    ASSERT_TRUE(GroundPoint(view, 500.5, 600.5, &u0, &v0));
    ASSERT_TRUE(GroundPoint(at, 500.5, 600.5, &u1, &v1));
    EXPECT_NEAR(u1 - u0, at.origin_u, 1e-9);
    EXPECT_NEAR(v1 - v0, at.origin_v, 1e-9);
    const double origin[2] = {at.origin_u, at.origin_v};
    for (int axis = 0; axis < 2; ++axis) {
      ASSERT_GE(origin[axis], 0.0);
      ASSERT_LT(origin[axis], 1.0);
      ++quarters[axis][static_cast<int>(4.0 * origin[axis])];
      double texels = 0;
      const double phase = std::modf(1024.0 * origin[axis], &texels);
      ++texel_quarters[axis][static_cast<int>(4.0 * phase)];
    }
  }
  for (int axis = 0; axis < 2; ++axis)
    for (int q = 0; q < 4; ++q) {
      EXPECT_GE(quarters[axis][q], 2) << "axis " << axis << " quarter " << q;
      EXPECT_GE(texel_quarters[axis][q], 2) << "axis " << axis << " texel quarter " << q;
    }
  // The checkerboard's edges (every 128 texels): the first 4 and the first 16 positions meet
  // them at evenly spread phases, one in each 128 / N texels, along U and along V alike (a view
  // along U and its mirror along V are scored over the same phases).
  for (int n : {4, 16}) {
    for (int axis = 0; axis < 2; ++axis) {
      std::vector<int> strata(n, 0);
      for (int k = 0; k < n; ++k) {
        const GrazingPlaneView at = ViewAtPosition(view, k);
        const double texels = 1024.0 * (axis == 0 ? at.origin_u : at.origin_v);
        ++strata[static_cast<int>(std::fmod(texels, 128.0) / (128.0 / n))];
      }
      for (int s = 0; s < n; ++s)
        EXPECT_EQ(strata[s], 1) << n << " positions, axis " << axis << ", phase stratum " << s;
    }
  }
}

TEST(ReferenceSampler, AveragesALinearTextureToItsCentreValue) {
  // r = (x + 0.5) / 64 on a 64-texel period, sampled well inside one period: the average over a
  // symmetric parallelogram of a linear function is its value at the centre.
  Image ramp(64, 64);
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) ramp.at(x, y) = {(x + 0.5f) / 64.0f, 0, 0, 1};
  ReferenceSampler sampler(ramp, 4.0);
  const TextureFootprint f{0.5, 0.3, 8.0f / 64, 2.0f / 64, -1.0f / 64, 3.0f / 64};
  EXPECT_NEAR(sampler.Sample(f).r, 0.5, 2e-3);
}

}  // namespace
}  // namespace aperture
