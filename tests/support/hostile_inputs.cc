#include "support/hostile_inputs.h"

#include <zlib.h>

#include <string>
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

namespace {

constexpr int kObjectsPerRow = 400;

std::string ObjectName(int i) { return "object-" + std::to_string(i); }

// Object i's place in its row, moved `shift` metres along x.
v1::Transform ObjectTransform(int i, double shift) {
  v1::Transform t;
  t.mutable_translation()->set_x(2.0 * (i % kObjectsPerRow) - kObjectsPerRow + shift);
  t.mutable_translation()->set_z(-20.0 - 2.0 * (i / kObjectsPerRow));
  return t;
}

}  // namespace

v1::Scene ManyObjectsScene(int objects) {
  v1::Scene scene;
  scene.set_name("many objects");
  v1::Material& material = *scene.add_materials();
  material.set_id("grey");
  material.mutable_base_color()->set_r(0.5f);
  material.mutable_base_color()->set_g(0.5f);
  material.mutable_base_color()->set_b(0.5f);
  v1::Mesh& mesh = *scene.add_meshes();
  mesh.set_id("marker");
  mesh.set_material_id("grey");
  v1::Polygon& triangle = *mesh.add_polygons();
  for (auto [x, z] : {std::pair{0.0, 0.0}, {0.5, -1.0}, {1.0, 0.0}}) {
    v1::Vec3& v = *triangle.add_vertices();
    v.set_x(x);
    v.set_z(z);
  }
  for (int i = 0; i < objects; ++i) {
    v1::Object& o = *scene.add_objects();
    o.set_mesh_id("marker");
    o.set_name(ObjectName(i));
    *o.mutable_transform() = ObjectTransform(i, 0);
  }
  return scene;
}

v1::SceneUpdate UpdateEveryObject(int objects) {
  v1::SceneUpdate update;
  for (int i = 0; i < objects; ++i) {
    v1::ObjectUpdate& o = *update.add_objects();
    o.set_name(ObjectName(i));
    *o.mutable_transform() = ObjectTransform(i, 0.5);
    if (i % 2 == 1) o.set_visibility(v1::VISIBILITY_HIDDEN);
  }
  return update;
}

v1::SceneUpdate UpdateOneObjectRepeatedly(int objects, int times) {
  v1::SceneUpdate update;
  for (int i = 0; i < times; ++i) {
    v1::ObjectUpdate& o = *update.add_objects();
    o.set_name(ObjectName(objects - 1));
    *o.mutable_transform() = ObjectTransform(objects - 1, 1e-5 * i);
  }
  return update;
}

}  // namespace aperture::testing
