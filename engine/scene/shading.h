// The shading model every renderer and reference shares (docs/SCENE.md): the view ray through a
// screen point, a plane's texture coordinates relative to the camera, a Lambert sun plus ambient
// light on the side of a surface that faces the camera, and exponential fog along the view ray.
// Inline: the raster's interior loop calls them per pixel.
#pragma once

#include <algorithm>
#include <cmath>

#include "base/image.h"
#include "scene/camera.h"
#include "scene/scene.h"
#include "scene/vec.h"

namespace aperture {

// Camera-space direction of the view ray through screen point (x, y) of a width x height frame
// (pixel corners at integers, row 0 at the top), with z = -1: the point at depth t is t times it.
inline Vec3 CameraRay(const FrustumTangents& frustum, int width, int height, double x, double y) {
  return {frustum.left + x / width * (frustum.right - frustum.left),
          frustum.top - y / height * (frustum.top - frustum.bottom), -1.0};
}

// A planar mapping's texture coordinates at the camera, moved by whole periods into [0, 1): the
// origin the renderers measure u and v from along a view ray (seed 000, eq. 1; seed 003, eq. 1),
// so that precision holds far from the world origin. Whole periods do not change a periodic
// texture's colours.
struct TextureOrigin {
  double u = 0, v = 0;
};
inline TextureOrigin TextureOriginAtCamera(const TextureMapping& mapping, const Vec3& camera) {
  const double u = Dot(mapping.su, camera) + mapping.u0;
  const double v = Dot(mapping.sv, camera) + mapping.v0;
  return {u - std::floor(u), v - std::floor(v)};
}

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
