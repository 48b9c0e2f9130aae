// A LoadScene request made into an engine scene: textures referenced by hash are taken from the
// texture store, file paths are refused, then the engine validates and builds the scene.
#pragma once

#include <memory>
#include <string>

#include "absl/status/statusor.h"
#include "aperture/v1/render_service.pb.h"
#include "scene/scene.h"
#include "texture_store.h"

namespace aperture {

struct LoadedScene {
  std::string id;  // SHA-256 of the request: the same scene loads to the same id
  std::shared_ptr<const Scene> scene;
};

absl::StatusOr<LoadedScene> BuildSceneFromRequest(const v1::LoadSceneRequest& request,
                                                  const TextureStore& textures);

}  // namespace aperture
