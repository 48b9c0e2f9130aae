#include "scene_peer_points.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "light_measure.h"
#include "scene/light_points.h"
#include "scene/object_placement.h"

namespace aperture {
namespace {

// Where a named object stands: world = linear * local + translation; `rotation` turns its lobes.
struct Placed {
  Mat3 linear, rotation;
  Vec3 translation;
};

// Each object's placement; none for a hidden one.
std::vector<std::optional<Placed>> PlaceObjects(const Scene& scene) {
  std::vector<std::optional<Placed>> out(scene.objects.size());
  for (size_t i = 0; i < scene.objects.size(); ++i) {
    const SceneObject& object = scene.objects[i];
    if (!object.visible) continue;
    auto placed = PlacementFromProto(object.transform, object.name);
    if (!placed.ok()) continue;
    const v1::Transform& t = object.transform;
    out[i] = Placed{placed->linear, YawPitchRoll(t.yaw_deg(), t.pitch_deg(), t.roll_deg()),
                    placed->translation};
  }
  return out;
}

}  // namespace

void ScenePeerPointsOf(const Scene& scene, const Camera& camera, int width, int height,
                       double time_s, double min_size, ScenePeerPoints& out) {
  const FrameView view(camera, width, height);
  const std::vector<std::optional<Placed>> placed = PlaceObjects(scene);
  out.points.clear();
  out.lights = 0;
  for (const PointLight& light : scene.lights.lights) {
    Vec3 position = light.position;
    const Mat3* rotation = nullptr;
    if (light.object >= 0) {
      const std::optional<Placed>& p = placed[light.object];
      if (!p) continue;
      position = p->linear * light.position + p->translation;
      rotation = &p->rotation;
    }
    const Vec3 to_light = position - camera.position;
    const Vec3 c = view.to_camera * to_light;
    if (!(-c.z > camera.near)) continue;
    // Off the frame by more than the largest point's radius: culled before any lighting.
    const double x = (c.x / -c.z - view.t.left) / view.sx, y = (view.t.top - c.y / -c.z) / view.sy;
    constexpr double kReach = 30 / 2.0 + 1;  // OsgSimPointSizes' largest size
    if (x < -kReach || y < -kReach || x > width + kReach || y > height + kReach) continue;
    const double distance = Length(to_light);
    Vec3 to_eye = to_light * (-1.0 / distance);
    if (rotation != nullptr) to_eye = rotation->Transposed() * to_eye;  // the lobe's frame
    LightView lv;
    lv.intensity_cd = LightIntensityTowards(light, to_eye, time_s, scene.lights.groups);
    if (!(lv.intensity_cd > 0)) continue;
    lv.drawn = true;
    lv.distance = distance;
    lv.lamp_px = light.radius_m / distance / view.sy;
    PeerLight pl = PeerLightOf(light, lv, camera.position, min_size);
    for (PeerPoint& p : pl.points) p.offset = to_light;  // where a light on an object is now
    int largest = 1;
    for (const PeerPoint& p : pl.points) largest = std::max(largest, p.point.size);
    const double reach = largest / 2.0 + 1;
    if (x < -reach || y < -reach || x > width + reach || y > height + reach) continue;
    out.points.insert(out.points.end(), pl.points.begin(), pl.points.end());
    ++out.lights;
  }
}

}  // namespace aperture
