// The shading model every renderer and reference shares (docs/SCENE.md): a Lambert sun plus
// ambient light on the side of a surface that faces the camera, and exponential fog along the
// view ray. Inline: the raster's interior loop calls them per pixel.
#pragma once

#include <algorithm>
#include <cmath>

#include "base/image.h"
#include "scene/scene.h"
#include "scene/vec.h"

namespace aperture {

// The light on a surface of material `mat` whose normal, turned towards the camera, is `facing`:
// 1 when the material is unlit, else ambient plus the sun by Lambert's cosine (alpha 1).
inline Rgba SurfaceLight(const Scene& scene, const Material& mat, const Vec3& facing) {
  if (mat.unlit) return {1, 1, 1, 1};
  const float cosine = static_cast<float>(std::max(0.0, Dot(facing, scene.sun_direction)));
  Rgba light = scene.ambient + scene.sun_color * cosine;
  light.a = 1;
  return light;
}

// `colour` seen through `distance` world units of the scene's fog (its alpha is the caller's to
// set again).
inline Rgba Fogged(const Scene& scene, const Rgba& colour, double distance) {
  if (scene.fog_density <= 0) return colour;
  const float keep = static_cast<float>(std::exp(-scene.fog_density * distance));
  return colour * keep + scene.fog_color * (1.0f - keep);
}

}  // namespace aperture
