// Turns a proto `Scene` into the engine's `Scene`: validates every field (naming the offending
// one in the error), loads textures (scene_textures.h), applies object transforms, triangulates
// concave polygons. The camera's proto form: frame/camera_proto.h.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include "absl/status/statusor.h"
#include "aperture/v1/scene.pb.h"
#include "scene/scene.h"
#include "store/shared_store.h"

namespace aperture {

// What one scene may hold; 0: no limit. Checked on the request before
// anything is decoded or built; an excess is InvalidArgument naming the limit.
struct SceneLimits {
  uint64_t polygons = 0;  // objects times their meshes' polygons (before triangulation)
  uint64_t vertices_per_polygon = 0;
  uint64_t textures = 0;
  // Light points, rows expanded: a row of a million lights is a line of a scene file, so even an
  // unlimited build keeps this bound.
  uint64_t lights = 1000000;
};

struct SceneBuildOptions {
  std::string base_dir;  // relative texture paths are resolved against this folder
  // When set, seed 000 tables and decoded packed textures come from (and go to) this store, and
  // the tables of materials filtered `aniso` are prepared while the scene is built.
  std::shared_ptr<const SharedStore> store;
  SceneLimits limits;
  // Asked between textures, objects and groups of table copies, and from the table builder's
  // worker threads (TableBuildOptions::stop: thread-safe); true: the build stops with Cancelled
  // (the caller knows whether a deadline or the client stopped it).
  std::function<bool()> stop;
};

absl::StatusOr<Scene> BuildScene(const v1::Scene& proto, const SceneBuildOptions& options = {});

}  // namespace aperture
