// A LoadScene request made into an engine scene: a built-in scene by name, or the scene sent with
// textures referenced by hash taken from the texture store (file paths are refused); then the
// engine validates and builds it.
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "absl/status/statusor.h"
#include "aperture/v1/render_service.pb.h"
#include "scene/scene.h"
#include "scene/scene_builder.h"
#include "scene/scene_memory.h"
#include "texture_store.h"

namespace aperture {

struct LoadedScene {
  std::string id;  // SHA-256 of the request: the same scene loads to the same id
  std::shared_ptr<const Scene> scene;
  std::optional<v1::Camera> default_camera;  // built-in scenes: the camera they are seen from
};

// The id a request loads to: SHA-256 of its deterministic bytes. Textures are referenced by
// content hash, so the same id always means the same scene.
std::string SceneRequestId(const v1::LoadSceneRequest& request);

// Asked with the scene's memory estimate once its textures are resolved, before anything is
// decoded or built; an error refuses the scene.
using AdmitScene = std::function<absl::Status(const SceneMemory&)>;

// `limits` bound what the scene may hold; `stop` (a deadline, a cancelled call) stops the build
// with Cancelled.
absl::StatusOr<LoadedScene> BuildSceneFromRequest(const v1::LoadSceneRequest& request,
                                                  const TextureStore& textures,
                                                  const SceneLimits& limits = {},
                                                  std::function<bool()> stop = nullptr,
                                                  const AdmitScene& admit = nullptr);

}  // namespace aperture
