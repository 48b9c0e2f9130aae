// The geometry check of a visual system: a dome of black and white 5-degree squares around the
// eye, and a channel's pixel -> direction mapping in closed form (a yaw offset and a frustum),
// independent of the engine, to say where each square must appear.
#pragma once

#include <utility>

#include "aperture/v1/scene.pb.h"
#include "scene/vec.h"

namespace aperture::testing {

constexpr double kDomeSquareDeg = 5;

// Squares of 5 degrees from azimuth -95 to 95 and elevation -30 to 30 on a sphere of 1000 around
// the origin, black and white alternating, unlit. Each square's four corners lie on the sphere
// and form an isosceles trapezoid, so the polygon is planar; its sides of constant azimuth lie on
// great circles through the eye and project onto the meridians exactly, its sides of constant
// elevation are chords (at most 0.02 degrees off the parallels).
v1::Scene CheckerDome();

// The direction at azimuth a (positive to the left, as yaw) and elevation e from an eye at the
// origin looking along -z (DESIGN.md's conventions).
Vec3 DomeDirection(double azimuth_deg, double elevation_deg);
// Azimuth and elevation of a unit direction, degrees.
std::pair<double, double> DomeAngles(const Vec3& direction);
// Whether the square at (azimuth, elevation) is white.
bool DomeWhite(double azimuth_deg, double elevation_deg);
// Whether an angle is more than `margin` degrees from the nearest square edge.
bool InsideSquare(double degrees, double margin);

double AngleBetweenDeg(const Vec3& u, const Vec3& v);

// A channel turned by `yaw_deg` about the eye's up axis, with an off-axis frustum, width x height
// pixels, seen from an eye at the origin turned by eye_yaw_deg and then pitched by eye_pitch_deg
// (DESIGN.md's conventions; the channel's turn comes after the eye's).
struct ChannelView {
  ChannelView(double yaw_deg, const v1::Frustum& frustum, int width, int height);
  // The unit direction through frame point (x, y) (pixel corners at integers, row 0 on top).
  Vec3 At(double x, double y) const;
  // The frame point a direction passes through, and whether it is in front of the channel.
  bool FramePoint(const Vec3& direction, double* x, double* y) const;

  double yaw_deg, left, right, bottom, top;  // the frustum's side tangents
  int width, height;
  double eye_yaw_deg = 0, eye_pitch_deg = 0;
};

}  // namespace aperture::testing
