// Gets a scene onto a server: a built-in scene by name (demo, airport, night, triangles, skewed,
// tris-N: the server builds it), or a scene JSON file or glTF model whose image textures are
// uploaded (skipping those the server already has) and then referenced by hash.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "aperture/v1/render_service.grpc.pb.h"
#include "gltf_import.h"

namespace aperture {

struct SceneOnServer {
  std::string scene_id;
  uint32_t polygons = 0;
  int textures_sent = 0, textures_skipped = 0;
  std::optional<v1::Camera> default_camera;  // built-in scenes: the camera they are seen from
  std::vector<GltfCamera> model_cameras;     // a glTF model's cameras, for --camera NAME
  std::vector<v1::NamedObject> objects;      // what a SceneUpdate can move, as loaded
};

// Whether the argument names a built-in scene (the server builds it) rather than a file.
bool IsBuiltinScene(const std::string& argument);

// A built-in scene's name or the path of a scene file (proto3 JSON of aperture.v1.Scene).
absl::StatusOr<SceneOnServer> LoadSceneOnServer(v1::Render::Stub& stub,
                                                const std::string& scene_argument);

}  // namespace aperture
