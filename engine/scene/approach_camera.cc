#include "scene/approach_camera.h"

#include <cmath>

namespace aperture {

Camera ApproachCamera(const RunwayDescription& runway, double distance_m, double pitch_deg,
                      double vertical_fov_deg) {
  const double h = Radians(runway.heading_deg);
  const Vec3 along{-std::sin(h), 0, -std::cos(h)};
  const double height =
      (distance_m + runway.papi_distance_m) * std::tan(Radians(runway.approach_slope_deg));
  Camera camera;
  camera.position = runway.threshold - along * distance_m + Vec3{0, height, 0};
  camera.yaw_deg = runway.heading_deg;
  camera.pitch_deg = pitch_deg;
  camera.vertical_fov_deg = vertical_fov_deg;
  camera.near = 1;
  return camera;
}

}  // namespace aperture
