#include "scene/camera.h"

#include <cmath>

#include "absl/strings/str_cat.h"

namespace aperture {

FrustumTangents ResolveFrustum(const Camera& camera, int width, int height) {
  if (camera.off_axis) {
    return {std::tan(Radians(camera.left_deg)), std::tan(Radians(camera.right_deg)),
            std::tan(Radians(camera.bottom_deg)), std::tan(Radians(camera.top_deg))};
  }
  const double top = std::tan(Radians(camera.vertical_fov_deg) / 2);
  const double right = top * static_cast<double>(width) / static_cast<double>(height);
  return {-right, right, -top, top};
}

absl::Status ValidateCamera(const Camera& c) {
  auto finite = [](double v) { return std::isfinite(v); };
  if (!IsFinite(c.position))
    return absl::InvalidArgumentError("camera position is not finite (NaN or infinity)");
  if (!finite(c.yaw_deg) || !finite(c.pitch_deg) || !finite(c.roll_deg))
    return absl::InvalidArgumentError("camera yaw/pitch/roll is not finite");
  if (!finite(c.view_yaw_deg) || !finite(c.view_pitch_deg) || !finite(c.view_roll_deg))
    return absl::InvalidArgumentError("camera view_offset yaw/pitch/roll is not finite");
  if (c.off_axis) {
    const double sides[] = {c.left_deg, c.right_deg, c.bottom_deg, c.top_deg};
    for (double s : sides)
      if (!finite(s) || std::abs(s) >= 89.0)
        return absl::InvalidArgumentError(
            "camera frustum angles must be finite and within (-89, 89) degrees");
    if (c.left_deg >= c.right_deg || c.bottom_deg >= c.top_deg)
      return absl::InvalidArgumentError("camera frustum needs left < right and bottom < top");
  } else if (!finite(c.vertical_fov_deg) || c.vertical_fov_deg <= 0 || c.vertical_fov_deg >= 179) {
    return absl::InvalidArgumentError(absl::StrCat(
        "camera vertical field of view ", c.vertical_fov_deg, " is outside (0, 179) degrees"));
  }
  if (!finite(c.near) || c.near <= 0)
    return absl::InvalidArgumentError("camera near plane must be finite and > 0");
  if (!finite(c.far) || (c.far != 0 && c.far <= c.near))
    return absl::InvalidArgumentError("camera far plane must be 0 (none) or beyond near");
  return absl::OkStatus();
}

}  // namespace aperture
