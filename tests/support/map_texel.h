// What the airport tests read of the built-in map: its colour at a world point on the ground.
#pragma once

#include <gtest/gtest.h>

#include <cmath>

#include "scene/scene.h"

namespace aperture::testing {

// The map's colour at world point (x, 0, z): its nearest texel, through the ground polygon's own
// texture mapping (the polygon of material "map").
inline Rgba MapAt(const Scene& scene, double x, double z) {
  for (const ScenePolygon& p : scene.polygons) {
    const Material& m = scene.materials[p.material];
    if (m.id != "map") continue;
    const Vec3 at{x, 0, z};
    TextureFootprint f;
    f.u = Dot(p.mapping.su, at) + p.mapping.u0;
    f.v = Dot(p.mapping.sv, at) + p.mapping.v0;
    f.u -= std::floor(f.u), f.v -= std::floor(f.v);
    return (*scene.textures[m.texture]->Sampler(FilterMode::kNearest))->Sample(f);
  }
  ADD_FAILURE() << "no map polygon";
  return {};
}

}  // namespace aperture::testing
