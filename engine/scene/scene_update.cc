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

// What an update makes of one object: its final visibility and transform, and the polygons that
// replace its range (unset: the range stays as it is).
struct ObjectChange {
  bool visible = true;
  const v1::Transform* transform = nullptr;  // the update's last transform for it, if any
  int entry = 0;                             // the update entry that named it last (errors)
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
  // Checked first: names, transforms and the environment's values cannot fail below.
  if (auto s = CheckSceneUpdate(*scene, update); !s.ok()) return s;
  // The final state of each object the update names (its last transform and visibility win).
  absl::flat_hash_map<size_t, ObjectChange> changes;
  for (int i = 0; i < update.objects_size(); ++i) {
    const v1::ObjectUpdate& o = update.objects(i);
    const auto index = static_cast<size_t>(ObjectIndex(*scene, o.name()));
    auto [it, inserted] = changes.try_emplace(index);
    ObjectChange& change = it->second;
    if (inserted) change.visible = scene->objects[index].visible;
    if (o.visibility() != v1::VISIBILITY_UNCHANGED)
      change.visible = o.visibility() == v1::VISIBILITY_SHOWN;
    if (o.has_transform()) change.transform = &o.transform();
    change.entry = i;
  }
  // Every object's polygons are placed before any is changed, so an object that cannot be placed
  // (its polygons degenerate under a new scale) leaves the scene as it was.
  for (auto& [index, change] : changes) {
    const SceneObject& object = scene->objects[index];
    if (!change.visible) {
      if (object.visible) change.polygons.emplace();  // hidden: its range empties
      continue;
    }
    if (!change.transform && object.visible) continue;  // shown already, not moved
    const std::string where = Where(change.entry, update.objects(change.entry).name());
    // A shown object without a new transform stands where its last one put it.
    auto placement =
        PlacementFromProto(change.transform ? *change.transform : object.transform, where);
    if (!placement.ok()) return placement.status();
    std::vector<ScenePolygon> placed;
    placed.reserve(object.mesh->polygons.size());
    if (auto s = PlaceMesh(*object.mesh, *placement, &placed); !s.ok())
      return Prefixed(s, where + ": ");
    change.polygons = std::move(placed);
  }

  // Commit: a moved object that keeps its polygon count is overwritten in place; otherwise its
  // range is replaced and the later objects' ranges shift.
  for (auto& [index, change] : changes) {
    SceneObject& object = scene->objects[index];
    if (change.transform) object.transform = *change.transform;
    if (change.polygons) ReplaceRange(index, *std::move(change.polygons), scene);
    object.visible = change.visible;
  }
  return SetEnvironment(update, scene);  // checked above: it cannot fail
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
