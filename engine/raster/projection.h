// Frame setup: transform the scene's polygons into camera space, clip them to the near (and far)
// plane in 3D, project, clip to the screen, and set up their screen-linear functions.
#pragma once

#include <vector>

#include "raster/screen_polygon.h"
#include "scene/camera.h"
#include "scene/scene.h"
#include "scene/shading.h"

namespace aperture {

struct FrameGeometry {
  int width = 0, height = 0;
  FrustumTangents frustum;
  // The camera's position and the rotation from world to camera space (what per-pixel lighting
  // needs to put a spot light and a surface point in one frame).
  Vec3 camera_position;
  Mat3 to_camera;
  std::vector<ScreenPolygon> polygons;

  // Camera-space direction through screen point (x, y), with z = -1: P = depth * Ray(x, y).
  Vec3 Ray(double x, double y) const { return CameraRay(frustum, width, height, x, y); }
};

// `margin`: how far beyond the image (in pixels) polygons must be kept for the filter aperture.
FrameGeometry ProjectScene(const Scene& scene, const Camera& camera, int width, int height,
                           double margin);

}  // namespace aperture
