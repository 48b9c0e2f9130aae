#include "support/hostile_inputs.h"

#include <zlib.h>

#include <utility>

namespace aperture::testing {

std::string PngDeclaring(uint32_t width, uint32_t height) {
  auto be32 = [](uint32_t v) {
    return std::string{static_cast<char>(v >> 24), static_cast<char>(v >> 16),
                       static_cast<char>(v >> 8), static_cast<char>(v)};
  };
  auto chunk = [&](const std::string& type, const std::string& data) {
    const std::string body = type + data;
    const uint32_t crc = static_cast<uint32_t>(
        crc32(0, reinterpret_cast<const Bytef*>(body.data()), static_cast<uInt>(body.size())));
    return be32(static_cast<uint32_t>(data.size())) + body + be32(crc);
  };
  const std::string ihdr = be32(width) + be32(height) + std::string{8, 2, 0, 0, 0};  // 8-bit RGB
  return std::string("\x89PNG\r\n\x1a\n", 8) + chunk("IHDR", ihdr) +
         chunk("IDAT", std::string("\x78\x9c\x03\x00\x00\x00\x00\x01", 8)) + chunk("IEND", "");
}

v1::LoadSceneRequest TexturedGroundScene(const std::string& sha256, uint32_t checkerboard,
                                         bool aniso) {
  v1::LoadSceneRequest request;
  v1::Scene& scene = *request.mutable_scene();
  v1::Texture& texture = *scene.add_textures();
  texture.set_id("t");
  if (checkerboard > 0)
    texture.mutable_checkerboard()->set_size(checkerboard);
  else
    (*request.mutable_texture_sha256())["t"] = sha256;
  v1::Material& material = *scene.add_materials();
  material.set_id("m");
  material.set_texture_id("t");
  if (aniso) material.set_filter(v1::TEXTURE_FILTER_ANISO);
  v1::Mesh& mesh = *scene.add_meshes();
  mesh.set_id("ground");
  mesh.set_material_id("m");
  v1::Polygon& quad = *mesh.add_polygons();
  for (auto [x, z] : {std::pair{-50, -50}, {-50, 50}, {50, 50}, {50, -50}}) {
    v1::Vec3& v = *quad.add_vertices();
    v.set_x(x);
    v.set_z(z);
  }
  return request;
}

}  // namespace aperture::testing
