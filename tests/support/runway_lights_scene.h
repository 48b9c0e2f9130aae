// A runway at night for the light benchmarks: a 3 km x 45 m runway along -z from its threshold at
// z = 0, lit by rows of light points (edge lights both sides every 60 m, centre line every 30 m
// turning red over the last 300 m, green threshold and red end bars, an approach light row with a
// crossbar), and the camera of an aircraft flying the 3 degree glide path towards it.
#pragma once

#include <string>
#include <vector>

#include "aperture/v1/scene.pb.h"
#include "scene/camera.h"

namespace aperture::testing {

struct RunwayLightsOptions {
  double exposure = 0.01;  // LightSettings.exposure
};

// The scene: the ground and the runway (dark, unlit) and the lights. Every light is omnidirectional
// and steady, and each row is a light group named after it ("edge-left", "centre", "approach",
// ...), so a light's group says which row it belongs to.
v1::Scene MakeRunwayLightsScene(const RunwayLightsOptions& options = {});

// The approach: the `slope_deg` glide path towards the aiming point `aim` (on the runway, 300 m
// past this scene's threshold), flying along `heading_deg` (a yaw: 0 flies along -z, 90 along
// -x), at `speed_mps` along the path, starting `start_distance_m` (horizontally) before the aiming
// point, looking along the path, 60 degrees vertical field of view.
struct GlidePath {
  Vec3 aim{0, 0, -300};
  double heading_deg = 0;
  double start_distance_m = 1800;
  double speed_mps = 70;
  double slope_deg = 3;

  Camera At(double time_s) const;
  // How far (horizontally) before the aiming point the camera is at `time_s`.
  double DistanceAt(double time_s) const;
};

}  // namespace aperture::testing
