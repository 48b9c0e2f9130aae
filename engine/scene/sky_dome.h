// What the sky shows in each direction where nothing covers the view: one colour, or the
// daylight model of a scene with a time of day (scene/daylight.h), in the scene's units.
#pragma once

#include "base/image.h"
#include "scene/preetham_sky.h"
#include "scene/vec.h"

namespace aperture {

struct SkyDome {
  bool analytic = false;  // false: every direction shows Scene::sky
  PreethamSky model;      // luminance in kcd/m2 (the sun held on the horizon once it has set)
  // Scene units per kcd/m2 of the model's sky, per channel: twilight's fading and its blue.
  Rgba scale{0, 0, 0, 1};
  Rgba floor{0, 0, 0, 1};  // the moonless night sky, added in every direction (scene units)

  // The sky towards unit world direction `dir` (+y up), alpha 1.
  Rgba Radiance(const Vec3& dir) const {
    const Rgba l = model.Radiance(dir);
    return {l.r * scale.r + floor.r, l.g * scale.g + floor.g, l.b * scale.b + floor.b, 1};
  }
};

}  // namespace aperture
