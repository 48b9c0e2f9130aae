// Spot lights: lamps with a beam (an aircraft's landing and taxi lights) that light the surfaces
// they reach, per pixel. A spot of intensity I on its axis gives a surface point at distance d,
// theta off its axis, whose normal makes the angle i with the direction to the lamp, the
// illuminance E = I f(theta) cos(i) T(d) / d^2 (the inverse-square cosine law; T the fog's
// transmission exp(-density d) along the beam), f the beam's fall-off: 1 within the inner cone,
// 0 beyond the outer one, and between them smoothstep of t = (cos theta - cos outer) /
// (cos inner - cos outer), f = t^2 (3 - 2 t). No shadows: every surface facing the lamp within
// the cone is lit. docs/SCENE.md, "Spot lights".
#pragma once

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "absl/container/flat_hash_map.h"
#include "absl/status/statusor.h"
#include "aperture/v1/scene.pb.h"
#include "base/image.h"
#include "scene/vec.h"

namespace aperture {

// At most this many spot lights per scene: each costs every pixel it may reach.
inline constexpr int kMaxSpotLights = 16;

// A spot light as the scene holds it, validated.
struct SpotLight {
  Vec3 position;  // world, or its object's frame when `object` >= 0
  Vec3 axis;      // unit, in the same frame
  double intensity_cd = 0;
  double cos_inner = 1, cos_outer = 0;  // of the cones' half-angles
  Rgba color{1, 1, 1, 1};
  int group = -1;   // index into SceneLights::groups, -1: none
  int object = -1;  // index into Scene::objects, -1: world
};

// The beam's fall-off f at cos(theta) (theta off the axis), for cos_outer <= cos_inner.
inline double SpotConeFalloff(double cos_theta, double cos_inner, double cos_outer) {
  if (!(cos_theta > cos_outer)) return 0;
  if (cos_theta >= cos_inner) return 1;
  const double t = (cos_theta - cos_outer) / (cos_inner - cos_outer);
  return t * t * (3 - 2 * t);
}

// Validates `spot` (errors name the field under `where`) and makes its lamp: `lamp` becomes the
// light point drawn where it is (same position, object, group, colour and intensity, its lobe the
// outer cone). `objects` resolves SpotLight.object.
absl::StatusOr<SpotLight> MakeSpotLight(const v1::SpotLight& spot, const std::string& where,
                                        const absl::flat_hash_map<std::string, size_t>& objects,
                                        v1::LightPoint* lamp);

// A spot light where it stands this frame, in one frame of reference with the points it lights:
// `weight` is its colour times its intensity (its group's scale applied) times the pixel value
// per lux of a white surface.
struct PlacedSpot {
  Vec3 position, axis;
  double cos_inner = 1, cos_outer = 0;
  Rgba weight{0, 0, 0, 0};
};

// What spot `s` adds to the light on a point `p` whose unit normal, turned to the side being
// seen, is `n` (zero when the lamp is behind that side or the point outside the cone), through
// fog of `fog_density` per unit.
inline void AddSpotLight(const PlacedSpot& s, const Vec3& p, const Vec3& n, double fog_density,
                         Rgba& light) {
  // Most points are outside the cone or behind the lamp: refused before any root or division.
  const Vec3 to_lamp = s.position - p;
  const double facing = Dot(n, to_lamp);  // d cos(i)
  if (!(facing > 0)) return;
  const double along = -Dot(s.axis, to_lamp);  // d cos(theta)
  if (!(along > 0)) return;
  const double d2 = Dot(to_lamp, to_lamp);
  if (!(along * along > s.cos_outer * s.cos_outer * d2)) return;  // cos_outer > 0
  const double d = std::sqrt(d2);
  const double f = SpotConeFalloff(along / d, s.cos_inner, s.cos_outer);
  if (!(f > 0)) return;
  double e = f * facing / (d2 * d);
  if (fog_density > 0) e *= std::exp(-fog_density * d);
  const float k = static_cast<float>(e);
  light.r += s.weight.r * k;
  light.g += s.weight.g * k;
  light.b += s.weight.b * k;
}

}  // namespace aperture
