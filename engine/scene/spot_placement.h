// Where a scene's spot lights stand in a frame: each attached one placed by its object's current
// transform (as its lamp, a light point, is), its group's switch and scale applied.
#pragma once

#include <vector>

#include "scene/scene.h"
#include "scene/spot_lights.h"

namespace aperture {

// The spot lights that shine this frame, in world coordinates less `origin` (a frame's camera
// position: points near the camera keep their precision far from the world origin), their
// weights in pixel value per lux (LightSettings: exposure x surface_exposure / pi). Spots of a
// hidden object or a switched-off group are left out.
std::vector<PlacedSpot> PlaceSpotLights(const Scene& scene, const Vec3& origin);

}  // namespace aperture
