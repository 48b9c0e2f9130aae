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

// A channel's view offset turns in the eye's frame: an eye pitched up 10 degrees with a channel
// turned 90 degrees left looks left along the eye's pitched horizon, level with the world's
// horizon's tilt seen sideways (its view axis is the eye's left, which pitch does not tilt).
TEST(Camera, ViewOffsetTurnsInTheEyesFrame) {
  Camera c;
  c.yaw_deg = 30;
  c.view_yaw_deg = 60;
  ExpectNear(Forward(c), {-1, 0, 0});  // yaw 30 + 60
  c = Camera{};
  c.pitch_deg = 10;
  c.view_yaw_deg = 90;
  ExpectNear(Forward(c), {-1, 0, 0});
  // The channel's up is the eye's up, tilted back by the eye's pitch.
  const double t = Radians(10);
  ExpectNear(Up(c), {0, std::cos(t), std::sin(t)});
  // A pitched channel on a yawed eye: yaw 90 (looking along -x), the channel 10 degrees up.
  c = Camera{};
  c.yaw_deg = 90;
  c.view_pitch_deg = 10;
  ExpectNear(Forward(c), {-std::cos(t), std::sin(t), 0});
}

TEST(Camera, ValidateNamesTheProblem) {
  Camera c;
  c.vertical_fov_deg = 0;
  EXPECT_NE(ValidateCamera(c).message().find("field of view"), std::string::npos);
  c = Camera{};
  c.position.x = NAN;
  EXPECT_NE(ValidateCamera(c).message().find("position"), std::string::npos);
  c = Camera{};
  c.view_pitch_deg = INFINITY;
  EXPECT_NE(ValidateCamera(c).message().find("view_offset"), std::string::npos);
}

}  // namespace
}  // namespace aperture
