// libFuzzer target over what a LoadScene may carry: the first byte chooses a
// scene file's JSON or a binary aperture.v1.Scene; the rest is parsed, weighed
// (EstimateSceneMemory) and built (BuildScene) under the server's kind of limits. Any input must
// give a scene or a clear error: never a crash, an over-read (ASan) or undefined behaviour.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "scene/scene_builder.h"
#include "scene/scene_file.h"
#include "scene/scene_memory.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  const std::string bytes(reinterpret_cast<const char*>(data) + 1, size - 1);
  aperture::v1::Scene scene;
  if (data[0] % 2 == 0) {
    auto parsed = aperture::ParseSceneJson(bytes);
    if (!parsed.ok()) return 0;
    scene = *std::move(parsed);
  } else if (!scene.ParseFromString(bytes)) {
    return 0;
  }
  // The budgets a server would apply, small enough to keep each run quick.
  auto memory = aperture::EstimateSceneMemory(scene);
  if (!memory.ok() || memory->total() > (64u << 20)) return 0;
  aperture::SceneBuildOptions options;
  options.limits.polygons = 20000;
  options.limits.vertices_per_polygon = 4096;
  options.limits.textures = 8;
  options.limits.lights = 20000;
  auto built = aperture::BuildScene(scene, options);
  // Lights are made within their limit: rows expanded, never past it.
  if (built.ok() && built->lights.lights.size() > options.limits.lights) std::abort();
  if (built.ok() && built->polygons.empty() && built->curved.empty() && scene.meshes_size() > 0 &&
      scene.objects_size() == 0) {
    // Meshes without objects are drawn once each: a mesh with polygons cannot vanish.
    for (const auto& mesh : scene.meshes())
      if (mesh.polygons_size() > 0) std::abort();
  }
  return 0;
}
