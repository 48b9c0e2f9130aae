// The pinhole camera: position, orientation (yaw, pitch, roll; DESIGN.md), frustum, near/far.
#pragma once

#include <string>

#include "absl/status/statusor.h"
#include "scene/vec.h"

namespace aperture {

struct Camera {
  Vec3 position;
  double yaw_deg = 0, pitch_deg = 0, roll_deg = 0;
  // A display channel's view turned from the eye's orientation (CIGI's view offsets), applied
  // after it: the channel looks where the eye would after turning by these angles.
  double view_yaw_deg = 0, view_pitch_deg = 0, view_roll_deg = 0;
  double vertical_fov_deg = 60;
  // Off-axis frustum (angles from the view axis); used when `off_axis` is set.
  bool off_axis = false;
  double left_deg = 0, right_deg = 0, bottom_deg = 0, top_deg = 0;
  double near = 0.1;
  double far = 0;  // 0: none

  // Columns: camera right (+x), up (+y) and back (+z) in world space: the eye's orientation, then
  // the channel's view offset in the eye's frame.
  Mat3 Orientation() const {
    return YawPitchRoll(yaw_deg, pitch_deg, roll_deg) *
           YawPitchRoll(view_yaw_deg, view_pitch_deg, view_roll_deg);
  }
};

// The frustum's side tangents for an image of the given size: a camera-space direction
// (x, y, -1) lands at pixel ((x - left) / (right - left) * W, (top - y) / (top - bottom) * H).
struct FrustumTangents {
  double left, right, bottom, top;
};
FrustumTangents ResolveFrustum(const Camera& camera, int width, int height);

// Checks finiteness and ranges; names the offending field.
absl::Status ValidateCamera(const Camera& camera);

}  // namespace aperture
