// Light points: the lights a pilot sees at night (runway, approach, taxiway and city lights, an
// aircraft's navigation lights and strobes), as the scene holds them and as each frame sees them.
// A light emits `intensity_cd` along its lobe's axis; what reaches the eye at distance d through
// fog of transmission T(d) is its illuminance E = I T(d) / d^2 (Allard's law), which the renderer
// spreads over a small footprint (render/light_pass.h; docs/SCENE.md, "Light points").
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "absl/container/flat_hash_map.h"
#include "absl/status/statusor.h"
#include "aperture/v1/scene.pb.h"
#include "base/image.h"
#include "scene/spot_lights.h"
#include "scene/vec.h"

namespace aperture {

// A light's directional lobe in the frame it was given in (world, or its object's).
struct LightLobe {
  Vec3 axis;                 // unit
  double tan_horizontal;     // tan of the beam's horizontal half-width
  double tan_vertical;       // tan of its vertical half-width
  double back_fraction = 0;  // of the peak, outside the beam
};

struct LightFlash {
  double period_s = 0, on_s = 0, phase_s = 0;  // period_s 0: steady
};

struct PointLight {
  Vec3 position;  // world, or its object's frame when `object` >= 0
  Rgba color{1, 1, 1, 1};
  double intensity_cd = 0;
  bool directional = false;
  LightLobe lobe;
  LightFlash flash;
  int group = -1;   // index into SceneLights::groups, -1: none
  int object = -1;  // index into Scene::objects (a named object), -1: world
  double radius_m = 0.1;
};

// What per-frame updates change of every light of a group.
struct LightGroup {
  std::string name;
  double intensity_scale = 1;
  bool visible = true;
};

struct LightSettings {
  double exposure = 0.01;    // pixel value per cd/m^2 of footprint luminance
  double min_size_px = 1.5;  // the footprint's smallest diameter
  // Surfaces lit by spot lights: pixel value = exposure x surface_exposure x albedo x E / pi.
  double surface_exposure = 1;
};

struct SceneLights {
  std::vector<PointLight> lights;
  std::vector<LightGroup> groups;
  absl::flat_hash_map<std::string, size_t> group_index;
  LightSettings settings;
  // Spot lights (scene/spot_lights.h); each one's lamp is also one of `lights`.
  std::vector<SpotLight> spots;
};

// The scene's light points from its `lights` and `light_rows` (rows expanded) and its spot lights
// (each adds its lamp to the light points), validated: errors name the field
// (`light_rows[2].spacing_m: must be > 0, is 0`). `object_index` resolves
// `LightPoint.object`; more than `max_lights` lights in all (0: no limit) is refused before any is
// made.
absl::StatusOr<SceneLights> BuildSceneLights(
    const v1::Scene& proto, const absl::flat_hash_map<std::string, size_t>& object_index,
    uint64_t max_lights);

// How many lights `proto` makes (its rows expanded, a lamp per spot light), from the counts alone;
// an error names a row that cannot be counted (a bad spacing, a row longer than the limit allows)
// or spot lights above kMaxSpotLights.
absl::StatusOr<uint64_t> CountSceneLights(const v1::Scene& proto, uint64_t max_lights);

// The intensity a light sends towards the eye, along the unit direction `to_eye` (from the light,
// in the lobe's frame): the lobe's falloff, its group's scale, zero while it flashes off at scene
// time `time_s` or its group is switched off. A lobe's intensity at angles (h, v) from its axis
// is I (1 - r^2) inside the elliptical beam r^2 = (tan h / tan H)^2 + (tan v / tan V)^2 <= 1,
// and never below back_fraction I (outside it, and behind the light).
double LightIntensityTowards(const PointLight& light, const Vec3& to_eye, double time_s,
                             const std::vector<LightGroup>& groups);

}  // namespace aperture
