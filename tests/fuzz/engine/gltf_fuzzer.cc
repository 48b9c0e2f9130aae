// libFuzzer target over the glTF import (issue 24, part 5): any bytes, as .glb when they start
// with its magic and as .gltf JSON otherwise, are a model or a clear error; external files are
// looked up in an empty folder, which they may not leave. A model that imports is triangles with
// finite coordinates and one uv per vertex or none.
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
  auto model = aperture::ImportGltfBytes(std::span(data, size), binary, folder, "fuzz");
  if (!model.ok()) return 0;
  for (const auto& mesh : model->scene.meshes())
    for (const auto& polygon : mesh.polygons()) {
      if (polygon.vertices_size() != 3) std::abort();
      if (polygon.uvs_size() != 0 && polygon.uvs_size() != 3) std::abort();
      for (const auto& v : polygon.vertices())
        if (!std::isfinite(v.x()) || !std::isfinite(v.y()) || !std::isfinite(v.z())) std::abort();
    }
  return 0;
}
