// The curved test scenes (raytrace mode only): a checkerboard sphere and a capped, lit
// checkerboard cylinder whose checks shrink to about a pixel, on black sky, each with the camera
// it is meant to be seen from. For the quality test and raytrace_quality_bench.
#pragma once

#include "aperture/v1/scene.pb.h"
#include "scene/camera.h"

namespace aperture {

enum class CurvedSceneKind { kSphere, kCylinder };

struct CurvedTestScene {
  v1::Scene scene;
  Camera camera;  // 60 degree vertical field of view, square images
};

// `checker_size` texels per side of the 8 x 8 checkerboard texture.
CurvedTestScene MakeCurvedTestScene(CurvedSceneKind kind, int checker_size = 256);

}  // namespace aperture
