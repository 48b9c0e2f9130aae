// libFuzzer target over the glTF import: any bytes, as .glb when they start
// with its magic and as .gltf JSON otherwise, are a model or a clear error; external files are
// looked up in an empty folder, which they may not leave. A model that imports is triangles with
// finite coordinates and one uv per vertex or none, and no more of them than the budget.
//
// The corpus (tests/fuzz/corpus/gltf) holds valid models and node graphs that are not trees
// (a child listed twice down 16 levels, two parents, a cycle, a root that is a child), a chain of
// 400 nodes, a strip placed by 60 nodes, an accessor count beyond its buffer, a structure of the
// wrong JSON type and nesting past the limit: the mutations of their counts, indices and
// children reach the node-graph check, the triangle count and the structure check.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <span>

#include "gltf_import.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const std::string folder = [] {
    const auto dir = std::filesystem::temp_directory_path() / "aperture-gltf-fuzz-empty";
    std::filesystem::create_directories(dir);
    return dir.string();
  }();
  const bool binary = size >= 4 && std::memcmp(data, "glTF", 4) == 0;
  // A budget far below the default: within the default, a few kilobytes of strip indices placed
  // by a thousand nodes make gigabytes of polygons, legitimately, past the fuzzer's memory limit.
  aperture::GltfImportOptions options;
  options.max_triangles = 100'000;
  auto model = aperture::ImportGltfBytes(std::span(data, size), binary, folder, "fuzz", options);
  if (!model.ok()) return 0;
  size_t triangles = 0;
  for (const auto& mesh : model->scene.meshes()) triangles += mesh.polygons_size();
  if (triangles > options.max_triangles) std::abort();
  for (const auto& mesh : model->scene.meshes())
    for (const auto& polygon : mesh.polygons()) {
      if (polygon.vertices_size() != 3) std::abort();
      if (polygon.uvs_size() != 0 && polygon.uvs_size() != 3) std::abort();
      for (const auto& v : polygon.vertices())
        if (!std::isfinite(v.x()) || !std::isfinite(v.y()) || !std::isfinite(v.z())) std::abort();
    }
  return 0;
}
