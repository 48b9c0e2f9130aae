// A camera on a runway's final approach: on the glide path that meets the runway at its PAPI's
// distance past the threshold (RunwayDescription.approach_slope_deg, papi_distance_m), looking
// down the landing direction, as the built-in airport's and night scene's cameras are.
#pragma once

#include "scene/airport_lighting.h"
#include "scene/camera.h"

namespace aperture {

// `distance_m` out from the threshold, pitched `pitch_deg` (negative: down) with the given
// vertical field of view; near 1 m.
Camera ApproachCamera(const RunwayDescription& runway, double distance_m, double pitch_deg,
                      double vertical_fov_deg);

}  // namespace aperture
