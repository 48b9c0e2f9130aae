#include "scene/scene_update.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <utility>
#include <vector>

#include "absl/container/flat_hash_map.h"
#include "absl/strings/str_cat.h"
#include "scene/object_placement.h"
#include "scene/scene_environment.h"

namespace aperture {
namespace {

// An object name quoted in an error is cut to this many characters, so that an error stays small
// whatever a request holds.
constexpr size_t kQuotedNameChars = 64;

std::string Where(int i, const std::string& name) {
  if (name.size() <= kQuotedNameChars)
    return absl::StrCat("update.objects[", i, "] ('", name, "')");
  return absl::StrCat("update.objects[", i, "] ('", name.substr(0, kQuotedNameChars), "...', ",
                      name.size(), " characters)");
}

absl::Status Prefixed(const absl::Status& s, const std::string& prefix) {
  return absl::Status(s.code(), absl::StrCat(prefix, s.message()));
}

int ObjectIndex(const Scene& scene, const std::string& name) {
  auto it = scene.object_index.find(name);
  return it == scene.object_index.end() ? -1 : static_cast<int>(it->second);
}

// Asks a stop test once per kUnits units of work (entries checked, polygons placed), so that a
// long update stops within a fraction of a millisecond of being told.
class StopEvery {
 public:
  explicit StopEvery(const std::function<bool()>& stop) : stop_(stop) {}
  bool operator()(size_t units) {
    if (!stop_) return false;
    done_ += units;
    if (done_ < kUnits) return false;
    done_ = 0;
    return stop_();
  }

 private:
  static constexpr size_t kUnits = 4096;
  const std::function<bool()>& stop_;
  size_t done_ = 0;
};

absl::Status StoppedError(const char* step, int entry, int entries) {
  return absl::CancelledError(
      absl::StrCat("the scene update was stopped (deadline or cancellation) ", step,
                   " at update.objects[", entry, "] of ", entries));
}

// The scene-wide values of `update` applied to `scene`, errors prefixed "update.".
absl::Status SetEnvironment(const v1::SceneUpdate& update, Scene* scene) {
  absl::Status s;
  if (update.has_sun()) s = SetSun(update.sun(), scene);
  if (s.ok() && update.has_ambient()) s = SetAmbient(update.ambient(), scene);
  if (s.ok() && update.has_fog()) s = SetFog(update.fog(), scene);
  if (s.ok() && update.has_sky()) s = SetSky(update.sky(), scene);
  if (!s.ok()) return Prefixed(s, "update.");
  // The hour's light wins over the values above while the scene has a time of day, so that
  // merged updates of skipped frames make the frame that applying them in turn does.
  if (update.has_time_of_day())
    return SetTimeOfDay(update.time_of_day(), /*update=*/true, "update.time_of_day", scene);
  if (update.has_sun() || update.has_ambient() || update.has_fog() || update.has_sky())
    ApplyDaylight(scene);
  return s;
}

// What an update makes of one object: its final visibility and transform, and the polygons that
// replace its range (unset: the range stays as it is).
struct ObjectChange {
  bool visible = true;
  const v1::Transform* transform = nullptr;  // the update's last transform for it, if any
  int entry = 0;                             // the update entry that named it last (errors)
  std::optional<std::vector<ScenePolygon>> polygons;
};

// The changed objects in scene order, by index into Scene::objects.
using OrderedChanges = std::vector<std::pair<size_t, ObjectChange>>;

// Lays the polygon array out again in one pass: each changed object's range becomes its new
// polygons, the polygons between the ranges (unnamed objects) move along, and every range after
// the first change starts where it now lies.
void LayOutRanges(OrderedChanges& changes, Scene* scene) {
  std::vector<ScenePolygon> old = std::move(scene->polygons);
  size_t total = old.size();
  for (const auto& [index, change] : changes)
    if (change.polygons) total = total - scene->objects[index].count + change.polygons->size();
  std::vector<ScenePolygon>& out = scene->polygons;
  out.clear();
  out.reserve(total);
  auto move_old = [&](size_t from, size_t to) {
    out.insert(out.end(), std::make_move_iterator(old.begin() + static_cast<ptrdiff_t>(from)),
               std::make_move_iterator(old.begin() + static_cast<ptrdiff_t>(to)));
  };
  size_t next_old = 0;  // the first polygon of `old` not moved yet
  auto change = changes.begin();
  for (size_t index = 0; index < scene->objects.size(); ++index) {
    SceneObject& object = scene->objects[index];
    const size_t old_first = object.first;
    move_old(next_old, old_first);  // the unnamed objects' polygons before its range
    next_old = old_first + object.count;
    object.first = out.size();
    if (change != changes.end() && change->first == index && change->second.polygons) {
      std::vector<ScenePolygon>& placed = *change->second.polygons;
      out.insert(out.end(), std::make_move_iterator(placed.begin()),
                 std::make_move_iterator(placed.end()));
      object.count = placed.size();
    } else {
      move_old(old_first, next_old);
    }
    if (change != changes.end() && change->first == index) ++change;
  }
  move_old(next_old, old.size());
}

}  // namespace

absl::Status CheckSceneUpdate(const Scene& scene, const v1::SceneUpdate& update,
                              const std::function<bool()>& stop) {
  StopEvery stopped(stop);
  for (int i = 0; i < update.objects_size(); ++i) {
    if (stopped(1)) return StoppedError("while it was checked", i, update.objects_size());
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
  for (int i = 0; i < update.light_groups_size(); ++i) {
    if (stopped(1)) return StoppedError("while its light groups were checked", i, 0);
    const v1::LightGroupUpdate& g = update.light_groups(i);
    const std::string where = absl::StrCat("update.light_groups[", i, "]");
    if (!scene.lights.group_index.contains(g.group()))
      return absl::InvalidArgumentError(
          absl::StrCat(where, ": no light group '", g.group().substr(0, kQuotedNameChars),
                       "' in scene '", scene.name, "' (lights are grouped by LightPoint.group)"));
    if (!v1::Visibility_IsValid(g.visibility()))
      return absl::InvalidArgumentError(
          absl::StrCat(where, ": visibility has unknown value ", g.visibility()));
    if (g.has_intensity_scale() &&
        !(g.intensity_scale().value() >= 0 && std::isfinite(g.intensity_scale().value())))
      return absl::InvalidArgumentError(
          absl::StrCat(where, ".intensity_scale: must be >= 0, is ", g.intensity_scale().value()));
  }
  Scene scratch;  // the environment's checks, on a throwaway copy of its few values
  scratch.time_of_day = scene.time_of_day;  // what an update's time of day keeps
  return SetEnvironment(update, &scratch);
}

absl::Status ApplySceneUpdate(const v1::SceneUpdate& update, Scene* scene,
                              const std::function<bool()>& stop) {
  // Checked first: names, transforms and the environment's values cannot fail below.
  if (auto s = CheckSceneUpdate(*scene, update, stop); !s.ok()) return s;
  const int entries = update.objects_size();
  StopEvery stopped(stop);
  // The final state of each object the update names (its last transform and visibility win).
  absl::flat_hash_map<size_t, ObjectChange> named;
  named.reserve(std::min(static_cast<size_t>(entries), scene->objects.size()));
  for (int i = 0; i < entries; ++i) {
    if (stopped(1)) return StoppedError("while it was gathered", i, entries);
    const v1::ObjectUpdate& o = update.objects(i);
    const auto index = static_cast<size_t>(ObjectIndex(*scene, o.name()));
    auto [it, inserted] = named.try_emplace(index);
    ObjectChange& change = it->second;
    if (inserted) change.visible = scene->objects[index].visible;
    if (o.visibility() != v1::VISIBILITY_UNCHANGED)
      change.visible = o.visibility() == v1::VISIBILITY_SHOWN;
    if (o.has_transform()) change.transform = &o.transform();
    change.entry = i;
  }
  OrderedChanges changes(std::make_move_iterator(named.begin()),
                         std::make_move_iterator(named.end()));
  named.clear();
  std::sort(changes.begin(), changes.end(),
            [](const auto& a, const auto& b) { return a.first < b.first; });

  // Every object's polygons are placed before any is changed, so an object that cannot be placed
  // (its polygons degenerate under a new scale) leaves the scene as it was.
  bool ranges_change = false;  // a range grows or shrinks: the array is laid out again
  for (auto& [index, change] : changes) {
    const SceneObject& object = scene->objects[index];
    if (stopped(object.mesh->polygons.size() + 1))
      return StoppedError("while its objects were placed", change.entry, entries);
    if (!change.visible) {
      if (object.visible) change.polygons.emplace();   // hidden: its range empties
    } else if (change.transform || !object.visible) {  // moved, or shown
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
    if (change.polygons && change.polygons->size() != object.count) ranges_change = true;
  }

  // Commit: a moved object that keeps its polygon count is overwritten in place; when a range
  // grows or shrinks, the whole array is laid out again once.
  if (ranges_change) LayOutRanges(changes, scene);
  for (auto& [index, change] : changes) {
    SceneObject& object = scene->objects[index];
    if (change.transform) object.transform = *change.transform;
    if (change.polygons && !ranges_change)
      std::move(change.polygons->begin(), change.polygons->end(),
                scene->polygons.begin() + static_cast<ptrdiff_t>(object.first));
    object.visible = change.visible;
  }
  for (const v1::LightGroupUpdate& g : update.light_groups()) {
    LightGroup& group = scene->lights.groups[scene->lights.group_index.at(g.group())];
    if (g.has_intensity_scale()) group.intensity_scale = g.intensity_scale().value();
    if (g.visibility() != v1::VISIBILITY_UNCHANGED)
      group.visible = g.visibility() == v1::VISIBILITY_SHOWN;
  }
  return SetEnvironment(update, scene);  // checked above: it cannot fail
}

void MergedSceneUpdate::Merge(const v1::SceneUpdate& later) {
  for (const v1::ObjectUpdate& o : later.objects()) {
    auto [it, inserted] = entry_.try_emplace(o.name(), merged_.objects_size());
    if (inserted) {
      *merged_.add_objects() = o;
      continue;
    }
    v1::ObjectUpdate& merged = *merged_.mutable_objects(it->second);
    if (o.has_transform()) *merged.mutable_transform() = o.transform();
    if (o.visibility() != v1::VISIBILITY_UNCHANGED) merged.set_visibility(o.visibility());
  }
  if (later.has_sun()) *merged_.mutable_sun() = later.sun();
  if (later.has_ambient()) *merged_.mutable_ambient() = later.ambient();
  if (later.has_fog()) *merged_.mutable_fog() = later.fog();
  if (later.has_sky()) *merged_.mutable_sky() = later.sky();
  if (later.has_time_of_day()) {
    // Each part from the later update where it sets it (an update's unset parts keep the scene's).
    const v1::TimeOfDay& t = later.time_of_day();
    v1::TimeOfDay& merged = *merged_.mutable_time_of_day();
    if (!t.utc().empty()) merged.set_utc(t.utc());
    if (t.has_place()) *merged.mutable_place() = t.place();
    if (t.turbidity() != 0) merged.set_turbidity(t.turbidity());
  }
  for (const v1::LightGroupUpdate& g : later.light_groups()) {
    auto [it, inserted] = light_group_entry_.try_emplace(g.group(), merged_.light_groups_size());
    if (inserted) {
      *merged_.add_light_groups() = g;
      continue;
    }
    v1::LightGroupUpdate& merged = *merged_.mutable_light_groups(it->second);
    if (g.has_intensity_scale()) *merged.mutable_intensity_scale() = g.intensity_scale();
    if (g.visibility() != v1::VISIBILITY_UNCHANGED) merged.set_visibility(g.visibility());
  }
  empty_ = empty_ && later.objects_size() == 0 && !later.has_sun() && !later.has_ambient() &&
           !later.has_fog() && !later.has_sky() && !later.has_time_of_day() &&
           later.light_groups_size() == 0;
}

v1::SceneUpdate MergedSceneUpdate::Take() {
  entry_.clear();
  light_group_entry_.clear();
  empty_ = true;
  return std::exchange(merged_, v1::SceneUpdate());
}

void MergeSceneUpdate(const v1::SceneUpdate& later, v1::SceneUpdate* earlier) {
  MergedSceneUpdate merged;
  merged.Merge(*earlier);
  merged.Merge(later);
  *earlier = merged.Take();
}

}  // namespace aperture
