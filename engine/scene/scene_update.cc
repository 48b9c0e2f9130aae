#include "scene/scene_update.h"

#include <optional>
#include <vector>

#include "absl/container/flat_hash_map.h"
#include "absl/strings/str_cat.h"
#include "scene/object_placement.h"
#include "scene/scene_environment.h"

namespace aperture {
namespace {

std::string Where(int i, const std::string& name) {
  return absl::StrCat("update.objects[", i, "] ('", name, "')");
}

absl::Status Prefixed(const absl::Status& s, const std::string& prefix) {
  return absl::Status(s.code(), absl::StrCat(prefix, s.message()));
}

int ObjectIndex(const Scene& scene, const std::string& name) {
  for (size_t i = 0; i < scene.objects.size(); ++i)
    if (scene.objects[i].name == name) return static_cast<int>(i);
  return -1;
}

// The scene-wide values of `update` applied to `scene`, errors prefixed "update.".
absl::Status SetEnvironment(const v1::SceneUpdate& update, Scene* scene) {
  absl::Status s;
  if (update.has_sun()) s = SetSun(update.sun(), scene);
  if (s.ok() && update.has_ambient()) s = SetAmbient(update.ambient(), scene);
  if (s.ok() && update.has_fog()) s = SetFog(update.fog(), scene);
  if (s.ok() && update.has_sky()) s = SetSky(update.sky(), scene);
  return s.ok() ? s : Prefixed(s, "update.");
}

// What an update makes of one object: its final visibility and placement, and the polygons that
// replace its range (unset: the range stays as it is).
struct ObjectChange {
  bool visible = true;
  std::optional<ObjectPlacement> placement;  // set by the update's last transform for it
  const v1::Transform* transform = nullptr;  // that transform
  std::optional<std::vector<ScenePolygon>> polygons;
};

// Replaces object `index`'s polygon range by `polygons`; the later objects' ranges shift.
void ReplaceRange(size_t index, std::vector<ScenePolygon> polygons, Scene* scene) {
  SceneObject& object = scene->objects[index];
  auto first = scene->polygons.begin() + static_cast<ptrdiff_t>(object.first);
  if (polygons.size() == object.count) {
    std::move(polygons.begin(), polygons.end(), first);
    return;
  }
  const auto count = static_cast<ptrdiff_t>(object.count);
  scene->polygons.erase(first, first + count);
  scene->polygons.insert(scene->polygons.begin() + static_cast<ptrdiff_t>(object.first),
                         std::make_move_iterator(polygons.begin()),
                         std::make_move_iterator(polygons.end()));
  for (size_t later = index + 1; later < scene->objects.size(); ++later)
    scene->objects[later].first = scene->objects[later].first - object.count + polygons.size();
  object.count = polygons.size();
}

}  // namespace

const SceneObject* FindObject(const Scene& scene, const std::string& name) {
  const int i = ObjectIndex(scene, name);
  return i < 0 ? nullptr : &scene.objects[static_cast<size_t>(i)];
}

absl::Status CheckSceneUpdate(const Scene& scene, const v1::SceneUpdate& update) {
  for (int i = 0; i < update.objects_size(); ++i) {
    const v1::ObjectUpdate& o = update.objects(i);
    if (ObjectIndex(scene, o.name()) < 0)
      return absl::InvalidArgumentError(
          absl::StrCat(Where(i, o.name()), ": no object of that name in scene '", scene.name,
                       "' (objects are named by Object.name)"));
    if (!v1::Visibility_IsValid(o.visibility()))
      return absl::InvalidArgumentError(
          absl::StrCat(Where(i, o.name()), ": visibility has unknown value ", o.visibility()));
    if (o.has_transform())
      if (auto p = PlacementFromProto(o.transform(), Where(i, o.name())); !p.ok())
        return p.status();
  }
  Scene scratch;  // the environment's checks, on a throwaway copy of its few values
  return SetEnvironment(update, &scratch);
}

absl::Status ApplySceneUpdate(const v1::SceneUpdate& update, Scene* scene) {
  if (auto s = CheckSceneUpdate(*scene, update); !s.ok()) return s;
  // The final state of each object the update names (its last transform and visibility win).
  absl::flat_hash_map<size_t, ObjectChange> changes;
  absl::flat_hash_map<size_t, int> last_mention;  // for errors: the update entry
  for (int i = 0; i < update.objects_size(); ++i) {
    const v1::ObjectUpdate& o = update.objects(i);
    const auto index = static_cast<size_t>(ObjectIndex(*scene, o.name()));
    auto [it, inserted] = changes.try_emplace(index);
    if (inserted) it->second.visible = scene->objects[index].visible;
    if (o.visibility() != v1::VISIBILITY_UNCHANGED)
      it->second.visible = o.visibility() == v1::VISIBILITY_SHOWN;
    if (o.has_transform()) {
      auto placement = PlacementFromProto(o.transform(), Where(i, o.name()));
      if (!placement.ok()) return placement.status();
      it->second.placement = *placement;
      it->second.transform = &o.transform();
    }
    last_mention[index] = i;
  }
  // Every change is computed before any is made, so an object that cannot be placed (its
  // polygons degenerate under a new scale) leaves the scene as it was.
  for (auto& [index, change] : changes) {
    const SceneObject& object = scene->objects[index];
    if (!change.visible) {
      if (object.visible) change.polygons.emplace();  // hidden: its range empties
      continue;
    }
    if (!change.placement && object.visible) continue;  // shown already, not moved
    std::vector<ScenePolygon> placed;
    placed.reserve(object.mesh->polygons.size());
    const ObjectPlacement& at = change.placement ? *change.placement : object.placement;
    if (auto s = PlaceMesh(*object.mesh, at, &placed); !s.ok()) {
      const int i = last_mention[index];
      return Prefixed(s, absl::StrCat(Where(i, update.objects(i).name()), ": "));
    }
    change.polygons = std::move(placed);
  }
  Scene environment;
  environment.sun_direction = scene->sun_direction;
  environment.sun_color = scene->sun_color;
  environment.ambient = scene->ambient;
  environment.fog_color = scene->fog_color;
  environment.fog_density = scene->fog_density;
  environment.sky = scene->sky;
  if (auto s = SetEnvironment(update, &environment); !s.ok()) return s;

  // Commit: a moved object that keeps its polygon count is overwritten in place; otherwise its
  // range is replaced and the later objects' ranges shift.
  for (auto& [index, change] : changes) {
    SceneObject& object = scene->objects[index];
    if (change.placement)
      object.placement = *change.placement, object.transform = *change.transform;
    if (change.polygons) ReplaceRange(index, *std::move(change.polygons), scene);
    object.visible = change.visible;
  }
  scene->sun_direction = environment.sun_direction;
  scene->sun_color = environment.sun_color;
  scene->ambient = environment.ambient;
  scene->fog_color = environment.fog_color;
  scene->fog_density = environment.fog_density;
  scene->sky = environment.sky;
  return absl::OkStatus();
}

void MergeSceneUpdate(const v1::SceneUpdate& later, v1::SceneUpdate* earlier) {
  // One entry per object: a stream whose frames are all superseded carries a bounded update.
  absl::flat_hash_map<std::string, int> entry;
  for (int i = 0; i < earlier->objects_size(); ++i) entry[earlier->objects(i).name()] = i;
  for (const v1::ObjectUpdate& o : later.objects()) {
    auto it = entry.find(o.name());
    if (it == entry.end()) {
      entry[o.name()] = earlier->objects_size();
      *earlier->add_objects() = o;
      continue;
    }
    v1::ObjectUpdate& merged = *earlier->mutable_objects(it->second);
    if (o.has_transform()) *merged.mutable_transform() = o.transform();
    if (o.visibility() != v1::VISIBILITY_UNCHANGED) merged.set_visibility(o.visibility());
  }
  if (later.has_sun()) *earlier->mutable_sun() = later.sun();
  if (later.has_ambient()) *earlier->mutable_ambient() = later.ambient();
  if (later.has_fog()) *earlier->mutable_fog() = later.fog();
  if (later.has_sky()) *earlier->mutable_sky() = later.sky();
}

}  // namespace aperture
