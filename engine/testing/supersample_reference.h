// A measuring stick for the raytrace mode on any scene (polygons, spheres, cylinders): each
// pixel's 1 x 1 square integrated by n x n stratified samples. Every sample's ray finds its
// nearest primitive (RayScene, then the exact plane or curved intersection in double), is shaded
// with the continuous texture (DESIGN.md: bilinear reconstruction of the full-resolution texture,
// periodic) at its own hit point, lit with its own normal (sun, ambient and spot lights), fogged
// by its own distance. n >= 64 gives the dense reference of the raytrace quality benchmark; n = 1
// (the pixel centre) or a few samples stand for renderers that point-sample or supersample a
// bilinear texture. Raster textures only.
#pragma once

#include "base/image.h"
#include "scene/camera.h"
#include "scene/scene.h"
#include "trace/ray_scene.h"

namespace aperture {

struct SupersampleOptions {
  int samples = 64;    // per pixel side
  bool jitter = true;  // jittered strata; false: stratum centres (n = 1: the pixel centre)
};

// Runs on the caller's oneTBB arena.
Image RenderSupersampled(const Scene& scene, const RayScene& rays, const Camera& camera, int width,
                         int height, const SupersampleOptions& options);

}  // namespace aperture
