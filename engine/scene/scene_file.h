// Scene files: the proto3 JSON mapping of aperture.v1.Scene, parsed by protobuf's own parser, and
// glTF models.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "aperture/v1/scene.pb.h"
#include "gltf_import.h"
#include "scene/scene.h"
#include "store/shared_store.h"

namespace aperture {

// Parses JSON text into the proto (unknown fields are errors).
absl::StatusOr<v1::Scene> ParseSceneJson(const std::string& json);
// A scene JSON file, or a glTF model (.gltf, .glb; import/gltf_import.h), whose notes on what is
// not drawn are logged as warnings and whose cameras go to `cameras` when given.
absl::StatusOr<v1::Scene> ReadSceneFile(const std::string& path,
                                        std::vector<GltfCamera>* cameras = nullptr);
std::string SceneToJson(const v1::Scene& scene);

// Reads, validates and builds: textures relative to the file's folder; tables and packed textures
// in `store` when one is given (scene_builder.h).
absl::StatusOr<Scene> LoadSceneFile(const std::string& path,
                                    std::shared_ptr<const SharedStore> store = nullptr);
// The build step of LoadSceneFile, for a scene already read from `path`.
absl::StatusOr<Scene> BuildSceneFile(const v1::Scene& proto, const std::string& path,
                                     std::shared_ptr<const SharedStore> store = nullptr);

}  // namespace aperture
