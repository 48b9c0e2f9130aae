// Seed 003's F = F2(F1(P)): cylindrical and spherical F1 on points with known angles, F2's scale,
// rotation and shift, and quads across the seam of the angle.
#include "trace/texture_mapping.h"

#include <gtest/gtest.h>

#include <cmath>

namespace aperture {
namespace {

TEST(TextureMapping, CylindricalAngleAndHeight) {
  PrimitiveMapping m;
  m.kind = MappingKind::kCylindrical;
  m.origin = {10, 2, -5};
  m.height = 4;
  // +z is angle 0, +x a quarter turn, -z half, -x three quarters; height 1 of 4 is 0.25.
  const Vec3 dirs[4] = {{0, 0, 1}, {1, 0, 0}, {0, 0, -1}, {-1, 0, 0}};
  for (int k = 0; k < 4; ++k) {
    const TexPoint t = F1(m, m.origin + dirs[k] * 3.0 + Vec3{0, 1, 0});
    EXPECT_NEAR(t.x, 0.25 * k, 1e-12);
    EXPECT_NEAR(t.z, 0.25, 1e-12);
  }
}

TEST(TextureMapping, SphericalPolesAndEquator) {
  PrimitiveMapping m;
  m.kind = MappingKind::kSpherical;
  m.origin = {0, 5, 0};
  EXPECT_NEAR(F1(m, {0, 7, 0}).z, 0.0, 1e-12);  // north pole
  EXPECT_NEAR(F1(m, {0, 3, 0}).z, 1.0, 1e-12);  // south pole
  const TexPoint e = F1(m, {-2, 5, 0});         // equator, -x
  EXPECT_NEAR(e.z, 0.5, 1e-12);
  EXPECT_NEAR(e.x, 0.75, 1e-12);
  // 45 degrees above the equator, towards +z.
  EXPECT_NEAR(F1(m, {0, 6, 1}).z, 0.25, 1e-12);
  // A rotated frame: the pole along world +x.
  m.axes = YawPitchRoll(0, 0, -90);  // roll turns the frame's y onto world +x
  const Vec3 pole = m.axes * Vec3{0, 1, 0};
  EXPECT_NEAR(F1(m, m.origin + pole * 2.0).z, 0.0, 1e-12);
}

TEST(TextureMapping, AffineScaleRotationShift) {
  // Scale by (2, 3), rotate 90 degrees, shift (0.5, -1): (1, 0) -> (2, 0) -> (0, 2) -> (0.5, 1).
  const Affine2 f = Affine2::ScaleRotateShift(2, 3, 90, 0.5, -1);
  const TexPoint p = f.Apply({1, 0});
  EXPECT_NEAR(p.x, 0.5, 1e-12);
  EXPECT_NEAR(p.z, 1.0, 1e-12);
  const TexPoint q = f.Apply({0, 1});  // (0, 3) -> (-3, 0) -> (-2.5, -1)
  EXPECT_NEAR(q.x, -2.5, 1e-12);
  EXPECT_NEAR(q.z, -1.0, 1e-12);
}

TEST(TextureMapping, QuadAcrossTheSeamStaysSmall) {
  // Four points just either side of angle 0 on a cylinder: x' = 0.999 and 0.001 become 0.999 and
  // 1.001, a quad 0.002 wide rather than 0.998.
  PrimitiveMapping m;
  m.kind = MappingKind::kCylindrical;
  m.f2 = Affine2::ScaleRotateShift(4, 1, 0, 0, 0);
  const double a = 2 * kPi * 0.001;
  const std::array<Vec3, 4> pts{{{-std::sin(a), 0.5, std::cos(a)},
                                 {std::sin(a), 0.5, std::cos(a)},
                                 {std::sin(a), 0.6, std::cos(a)},
                                 {-std::sin(a), 0.6, std::cos(a)}}};
  const auto q = MapQuad(m, pts);
  EXPECT_NEAR(q[0].x, 4 * 0.999, 1e-9);
  EXPECT_NEAR(q[1].x, 4 * 1.001, 1e-9);
  EXPECT_NEAR(q[2].x - q[3].x, 4 * 0.002, 1e-9);
  EXPECT_NEAR(q[3].z - q[0].z, 0.1, 1e-12);
  FragmentSet set;
  BuildFragments(q, {}, &set);
  EXPECT_NEAR(set.quad_area, 4 * 0.002 * 0.1, 1e-9);
}

}  // namespace
}  // namespace aperture
