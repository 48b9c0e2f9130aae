#include "scene/scene_memory.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <map>
#include <set>
#include <span>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "scene/encoded_texture.h"
#include "scene/light_points.h"
#include "scene/scene.h"

namespace aperture {
namespace {

absl::StatusOr<EncodedTextureInfo> TextureCost(const v1::Texture& texture, bool read_files) {
  switch (texture.source_case()) {
    case v1::Texture::kEncoded:
      return EstimateEncodedTexture(std::span(
          reinterpret_cast<const uint8_t*>(texture.encoded().data()), texture.encoded().size()));
    case v1::Texture::kCheckerboard: {
      const uint32_t size =
          texture.checkerboard().size() == 0 ? 1024 : texture.checkerboard().size();
      return RasterTextureCost(std::min<uint32_t>(size, 8192), std::min<uint32_t>(size, 8192));
    }
    case v1::Texture::kFile: {
      if (!read_files) return EncodedTextureInfo{};
      auto in = OIIO::ImageInput::open(texture.file());
      if (!in) return EncodedTextureInfo{};  // the build names the problem
      return RasterTextureCost(static_cast<uint32_t>(std::max(0, in->spec().width)),
                               static_cast<uint32_t>(std::max(0, in->spec().height)));
    }
    case v1::Texture::SOURCE_NOT_SET:
      break;
  }
  return EncodedTextureInfo{};
}

}  // namespace

std::string SceneMemory::ToString() const {
  auto mib = [](uint64_t b) { return b / double(1 << 20); };
  return absl::StrFormat("%.1f MiB (textures %.1f, aniso tables %.1f, geometry %.1f)", mib(total()),
                         mib(texture_bytes), mib(table_bytes), mib(geometry_bytes));
}

absl::StatusOr<SceneMemory> EstimateSceneMemory(const v1::Scene& scene, bool read_files) {
  SceneMemory memory;
  std::map<std::string, EncodedTextureInfo> textures;
  for (int i = 0; i < scene.textures_size(); ++i) {
    auto cost = TextureCost(scene.textures(i), read_files);
    if (!cost.ok())
      return absl::Status(cost.status().code(),
                          absl::StrCat("textures[", i, "] ('", scene.textures(i).id(),
                                       "'): ", cost.status().message()));
    memory.texture_bytes += cost->texture_bytes;
    textures[scene.textures(i).id()] = *cost;
  }
  std::set<std::string> tabled;  // a texture's table is built once, whatever refers to it
  for (const v1::Material& material : scene.materials())
    if (material.filter() == v1::TEXTURE_FILTER_ANISO &&
        tabled.insert(material.texture_id()).second)
      if (auto it = textures.find(material.texture_id()); it != textures.end())
        memory.table_bytes += it->second.table_bytes;

  // A polygon of v vertices becomes one polygon (convex) or v - 2 triangles (concave).
  constexpr uint64_t kPolygon = sizeof(ScenePolygon) + 4 * sizeof(Vec3);
  std::map<std::string, uint64_t> mesh_bytes;
  for (const v1::Mesh& mesh : scene.meshes()) {
    uint64_t bytes = 0;
    for (const v1::Polygon& polygon : mesh.polygons())
      bytes += kPolygon * static_cast<uint64_t>(std::max(1, polygon.vertices_size() - 2));
    mesh_bytes[mesh.id()] = bytes;
  }
  if (scene.objects_size() == 0) {
    for (const auto& [id, bytes] : mesh_bytes) memory.geometry_bytes += bytes;
  } else {
    for (const v1::Object& object : scene.objects())
      if (auto it = mesh_bytes.find(object.mesh_id()); it != mesh_bytes.end())
        memory.geometry_bytes += it->second;
  }
  // Light points, rows expanded (a row that cannot be counted is refused by the build).
  if (auto lights = CountSceneLights(scene, 0); lights.ok())
    memory.geometry_bytes += *lights * sizeof(PointLight);
  return memory;
}

}  // namespace aperture
