#include "scene/camera.h"

#include <gtest/gtest.h>

namespace aperture {
namespace {

Vec3 Forward(const Camera& c) { return c.Orientation() * Vec3{0, 0, -1}; }
Vec3 Up(const Camera& c) { return c.Orientation() * Vec3{0, 1, 0}; }

void ExpectNear(const Vec3& a, const Vec3& b) {
  EXPECT_NEAR(a.x, b.x, 1e-12);
  EXPECT_NEAR(a.y, b.y, 1e-12);
  EXPECT_NEAR(a.z, b.z, 1e-12);
}

TEST(Camera, YawZeroLooksAlongMinusZ) { ExpectNear(Forward(Camera{}), {0, 0, -1}); }

TEST(Camera, YawNinetyLooksAlongMinusX) {
  Camera c;
  c.yaw_deg = 90;
  ExpectNear(Forward(c), {-1, 0, 0});
}

TEST(Camera, GrazingPlaneCameraMatchesDesign) {
  const Camera c{.position = {0, 1, 0}, .pitch_deg = -5};
  const double t = Radians(5);
  ExpectNear(Forward(c), {0, -std::sin(t), -std::cos(t)});
  ExpectNear(Up(c), {0, std::cos(t), -std::sin(t)});
}

TEST(Camera, PositiveRollTurnsTheImageCounterClockwise) {
  // Rolling the camera clockwise (right wing down) tilts the world's up vector, as seen in the
  // image, to the left: counter-clockwise.
  Camera c;
  c.roll_deg = 30;
  const Mat3 to_camera = c.Orientation().Transposed();
  const Vec3 world_up_in_camera = to_camera * Vec3{0, 1, 0};
  EXPECT_LT(world_up_in_camera.x, 0);  // points left of the image's vertical
  EXPECT_NEAR(world_up_in_camera.y, std::cos(Radians(30)), 1e-12);
}

TEST(Camera, ValidateNamesTheProblem) {
  Camera c;
  c.vertical_fov_deg = 0;
  EXPECT_NE(ValidateCamera(c).message().find("field of view"), std::string::npos);
  c = Camera{};
  c.position.x = NAN;
  EXPECT_NE(ValidateCamera(c).message().find("position"), std::string::npos);
}

}  // namespace
}  // namespace aperture
