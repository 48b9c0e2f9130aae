#include "scene/spot_placement.h"

#include "scene/object_placement.h"

namespace aperture {

std::vector<PlacedSpot> PlaceSpotLights(const Scene& scene, const Vec3& origin) {
  std::vector<PlacedSpot> placed;
  const SceneLights& lights = scene.lights;
  if (lights.spots.empty()) return placed;
  const double per_lux =
      lights.settings.exposure * lights.settings.surface_exposure / kPi;  // white surface
  for (const SpotLight& spot : lights.spots) {
    double scale = 1;
    if (spot.group >= 0) {
      const LightGroup& g = lights.groups[spot.group];
      if (!g.visible) continue;
      scale = g.intensity_scale;
    }
    Vec3 position = spot.position, axis = spot.axis;
    if (spot.object >= 0) {
      const SceneObject& object = scene.objects[spot.object];
      if (!object.visible) continue;
      auto placement = PlacementFromProto(object.transform, object.name);
      if (!placement.ok()) continue;  // validated when it was set
      const v1::Transform& t = object.transform;
      position = placement->linear * spot.position + placement->translation;
      // Turned with the object, not sheared by its scale (as the lamp's lobe is).
      axis = YawPitchRoll(t.yaw_deg(), t.pitch_deg(), t.roll_deg()) * spot.axis;
    }
    const float w = static_cast<float>(spot.intensity_cd * scale * per_lux);
    if (!(w > 0)) continue;
    placed.push_back({position - origin,
                      axis,
                      spot.cos_inner,
                      spot.cos_outer,
                      {spot.color.r * w, spot.color.g * w, spot.color.b * w, 0}});
  }
  return placed;
}

}  // namespace aperture
