// Gets a scene onto a server: reads `demo` or a scene JSON file, uploads its image textures
// (skipping those the server already has), then loads the scene with textures referenced by hash.
#pragma once

#include <string>

#include "absl/status/statusor.h"
#include "aperture/v1/render_service.grpc.pb.h"

namespace aperture {

struct SceneOnServer {
  std::string scene_id;
  uint32_t polygons = 0;
  int textures_sent = 0, textures_skipped = 0;
};

// `demo` or the path of a scene file (proto3 JSON of aperture.v1.Scene).
absl::StatusOr<SceneOnServer> LoadSceneOnServer(v1::Render::Stub& stub,
                                                const std::string& scene_argument);

}  // namespace aperture
