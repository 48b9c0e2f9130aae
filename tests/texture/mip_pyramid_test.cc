#include "texture/mip_pyramid.h"

#include <gtest/gtest.h>

#include <cmath>

namespace aperture {
namespace {

Image Ramp(int n) {
  Image img(n, n);
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) img.at(x, y) = {float(x), float(y), float(x * y), 1};
  return img;
}

TEST(MipPyramid, LevelsAreBoxAverages) {
  const MipPyramid p(Ramp(8));
  ASSERT_EQ(p.levels(), 4);
  EXPECT_EQ(p.level(1).width(), 4);
  EXPECT_FLOAT_EQ(p.level(1).at(1, 2).r, 2.5f);  // mean of x = 2, 3
  EXPECT_FLOAT_EQ(p.level(1).at(1, 2).g, 4.5f);  // mean of y = 4, 5
  EXPECT_FLOAT_EQ(p.level(3).at(0, 0).r, 3.5f);
}

TEST(MipPyramid, RectangularTexturesCollapseOneAxis) {
  const MipPyramid p(Image(8, 2, {1, 1, 1, 1}));
  EXPECT_EQ(p.levels(), 4);
  EXPECT_EQ(p.level(3).width(), 1);
  EXPECT_EQ(p.level(3).height(), 1);
  EXPECT_FLOAT_EQ(p.level(3).at(0, 0).g, 1.0f);
}

TEST(MipPyramid, BilinearHitsTexelCentresAndWraps) {
  const MipPyramid p(Ramp(8));
  // Texel (3, 5) is centred at ((3.5) / 8, (5.5) / 8).
  const Rgba c = p.Bilinear(0, 3.5 / 8, 5.5 / 8);
  EXPECT_FLOAT_EQ(c.r, 3);
  EXPECT_FLOAT_EQ(c.g, 5);
  // Halfway between texel 7 and texel 0 across the periodic seam.
  EXPECT_FLOAT_EQ(p.Bilinear(0, 0.0, 0.5 / 8).r, 3.5f);
  EXPECT_FLOAT_EQ(p.Nearest(0.999, 0.0).r, 7.0f);
}

TEST(MipPyramid, TrilinearOfAConstantIsThatConstant) {
  const MipPyramid p(Image(64, 64, {0.3f, 0.5f, 0.7f, 1}));
  for (float d : {0.0f, 0.001f, 0.02f, 0.3f, 5.0f}) {
    TextureFootprint f{0.37, 0.81, d, d * 0.5f, -d * 0.2f, d};
    const Rgba c = p.Trilinear(f);
    EXPECT_FLOAT_EQ(c.r, 0.3f);
    EXPECT_FLOAT_EQ(c.b, 0.7f);
  }
}

TEST(MipPyramid, TrilinearPicksTheLevelOfTheLongerAxis) {
  const MipPyramid p(Ramp(16));
  // A footprint 4 texels long along x (level 2) at the centre of level-2 texel (1, 1).
  TextureFootprint f{1.5 * 4 / 16, 1.5 * 4 / 16, 4.0f / 16, 0, 0, 1.0f / 16};
  const Rgba c = p.Trilinear(f);
  EXPECT_FLOAT_EQ(c.r, p.level(2).at(1, 1).r);
  // Halfway between levels 1 and 2 in log2: a blend of both.
  f.dudx = std::pow(2.0f, 1.5f) / 16;
  const Rgba blend = p.Trilinear(f);
  const float l1 = p.Bilinear(1, f.u, f.v).r, l2 = p.Bilinear(2, f.u, f.v).r;
  EXPECT_NEAR(blend.r, 0.5f * (l1 + l2), 1e-4);
}

}  // namespace
}  // namespace aperture
