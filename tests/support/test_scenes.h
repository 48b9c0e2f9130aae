// Small scenes built in code for tests.
#pragma once

#include <vector>

#include "aperture/v1/scene.pb.h"
#include "base/image.h"
#include "scene/vec.h"

namespace aperture::testing {

struct FlatPolygon {
  std::vector<Vec3> vertices;
  Rgba colour;  // a: the material's alpha (1 - transparency) when alpha_mode is MASK or BLEND
  v1::AlphaMode alpha_mode = v1::ALPHA_MODE_OPAQUE;
  float alpha_cutoff = 0;  // MASK: 0 is the default, 0.5
};

// Unlit, untextured polygons (one material each) over a sky colour; no fog.
v1::Scene MakeFlatScene(const std::vector<FlatPolygon>& polygons, Rgba sky);

// DESIGN.md's grazing plane: y = 0, u = x / 4, v = z / 4, a checkerboard of 8 x 8 cells on
// 1024 x 1024 texels; the square polygon spans `half_extent` around (cx, cz).
v1::Scene MakeGrazingPlaneScene(double half_extent, double cx = 0, double cz = 0);

}  // namespace aperture::testing
