// Turns a proto `Scene` into the engine's `Scene`: validates every field (naming the offending
// one in the error), loads textures, applies object transforms, triangulates concave polygons.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "absl/status/statusor.h"
#include "aperture/v1/scene.pb.h"
#include "scene/camera.h"
#include "scene/scene.h"
#include "store/shared_store.h"

namespace aperture {

// What one scene may hold (issue 23, part 4); 0: no limit. Checked on the request before
// anything is decoded or built; an excess is InvalidArgument naming the limit.
struct SceneLimits {
  uint64_t polygons = 0;  // objects times their meshes' polygons (before triangulation)
  uint64_t vertices_per_polygon = 0;
  uint64_t textures = 0;
};

struct SceneBuildOptions {
  std::string base_dir;  // relative texture paths are resolved against this folder
  // When set, seed 000 tables and decoded packed textures come from (and go to) this store, and
  // the tables of materials filtered `aniso` are prepared while the scene is built.
  std::shared_ptr<const SharedStore> store;
  SceneLimits limits;
  // Asked between textures, objects and groups of table copies; true: the build stops with
  // Cancelled (the caller knows whether a deadline or the client stopped it).
  std::function<bool()> stop;
};

// The engine's filter for a proto filter value; nullopt for TEXTURE_FILTER_DEFAULT and for
// values this build does not know.
std::optional<FilterMode> FilterModeFromProto(int filter);

absl::StatusOr<Scene> BuildScene(const v1::Scene& proto, const SceneBuildOptions& options = {});

// Camera from its proto form (defaults: fov 60, near 0.1), validated.
absl::StatusOr<Camera> CameraFromProto(const v1::Camera& proto);
v1::Camera CameraToProto(const Camera& camera);

}  // namespace aperture
