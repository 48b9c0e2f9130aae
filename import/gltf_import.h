// glTF 2.0 models (.gltf with external or embedded buffers, .glb) as Aperture scenes, read by
// tinygltf (Debian's libtinygltf-dev). Proto only, no engine code: the engine's scene files and
// the client's uploads both go through it.
//
// Before anything is built, the file's JSON structure is checked (gltf_json_structure.h), its node
// graph is checked to be a forest (gltf_node_tree.h) and its triangles are counted against
// GltfImportOptions::max_triangles (gltf_triangle_count.h).
//
// Mapping (docs/SCENE.md, "glTF models"): the default scene's node hierarchy (matrices and TRS)
// is applied to the vertices, one mesh per node that has one; triangle primitives (lists, strips
// and fans) with or without indices become triangles, with TEXCOORD_0 as their uvs;
// baseColorFactor and baseColorTexture (with KHR_texture_transform) become the material;
// KHR_lights_punctual's point and spot lights become light points at their nodes.
// External images stay files (relative to the model, which they may not leave); embedded ones
// are carried as encoded bytes. What Aperture does not draw is listed in `notes`, once each.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "aperture/v1/scene.pb.h"

namespace aperture {

struct GltfCamera {
  std::string name;  // the node's name, else "camera<i>" of the node's camera
  v1::Camera camera;
};

struct ImportedModel {
  v1::Scene scene;
  std::vector<GltfCamera> cameras;
  // Parts of the file that are not drawn or drawn differently, one line each ("2 skins ignored").
  std::vector<std::string> notes;
};

// The default triangle budget of an import: aperture-server's default --max-scene-polygons, so
// that a model the client imports is one a server with default limits loads.
inline constexpr uint64_t kDefaultGltfMaxTriangles = 4'000'000;

struct GltfImportOptions {
  // Most triangles an import may make, counted before any is allocated: each mesh once for every
  // node that places it. ExpandModels applies it to a scene's models together.
  uint64_t max_triangles = kDefaultGltfMaxTriangles;
};

// True for the file names ImportGltf reads (.gltf, .glb; any case).
bool IsGltfPath(const std::string& path);

// Errors name the element: "meshes[3].primitives[0].indices: index 912 out of range 0..899".
absl::StatusOr<ImportedModel> ImportGltf(const std::string& path,
                                         const GltfImportOptions& options = {});
// The same from the file's bytes (`binary`: .glb); external files are read from `folder`, which
// they may not leave. The fuzz target's entry point.
absl::StatusOr<ImportedModel> ImportGltfBytes(std::span<const uint8_t> bytes, bool binary,
                                              const std::string& folder, const std::string& name,
                                              const GltfImportOptions& options = {});

// Resolves a scene file's glTF model references (Scene.models, Object.model_id): each model's
// file (relative to `scene_dir`; outside it only with `allow_any_path`) imported, its triangles
// made one mesh whose id is the model's, its materials and textures given ids "<model>/...", its
// image files made relative to `scene_dir`; objects placing it get that mesh. The models' notes
// go to `notes`, prefixed with their file.
absl::Status ExpandModels(v1::Scene& scene, const std::string& scene_dir, bool allow_any_path,
                          std::vector<std::string>* notes, const GltfImportOptions& options = {});

}  // namespace aperture
