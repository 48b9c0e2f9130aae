#include "support/hostile_scenes.h"

#include <cmath>
#include <random>
#include <string>

#include "absl/strings/str_cat.h"

namespace aperture::testing {
namespace {

constexpr int kColours = 8;
constexpr double kPi = 3.14159265358979323846;

// Unlit flat materials "m0".."m7" and an empty mesh "triangles".
v1::Scene FlatScene(const std::string& name) {
  v1::Scene scene;
  scene.set_name(name);
  scene.mutable_sky()->set_r(0.5f);
  scene.mutable_sky()->set_g(0.7f);
  scene.mutable_sky()->set_b(0.9f);
  for (int i = 0; i < kColours; ++i) {
    v1::Material& m = *scene.add_materials();
    m.set_id(absl::StrCat("m", i));
    m.set_unlit(true);
    m.mutable_base_color()->set_r((37 * i % 255) / 255.0f);
    m.mutable_base_color()->set_g((91 * i % 255) / 255.0f);
    m.mutable_base_color()->set_b((53 * i % 255) / 255.0f);
  }
  scene.add_meshes()->set_id("triangles");
  return scene;
}

// An equilateral triangle facing +z, of circumradius `radius`, turned by `turn` radians.
void AddTriangle(v1::Scene& scene, double cx, double cy, double radius, double turn, double z) {
  v1::Mesh& mesh = *scene.mutable_meshes(0);
  v1::Polygon& p = *mesh.add_polygons();
  p.set_material_id(absl::StrCat("m", mesh.polygons_size() % kColours));
  for (int k = 0; k < 3; ++k) {
    v1::Vec3& v = *p.add_vertices();
    v.set_x(cx + radius * std::cos(turn + k * 2 * kPi / 3));
    v.set_y(cy + radius * std::sin(turn + k * 2 * kPi / 3));
    v.set_z(z);
  }
}

}  // namespace

v1::Scene CoplanarCrowdScene(bool spread) {
  v1::Scene scene = FlatScene(spread ? "coplanar-spread" : "coplanar");
  std::mt19937 rng(47);
  constexpr int kCount = 8000, kDeep = 27;
  constexpr double kSide = 0.01;
  const double area = std::sqrt(3.0) / 4 * kSide * kSide;
  const double patch = std::sqrt(kCount * area / kDeep);  // the square their centres fill
  std::uniform_real_distribution<double> centre(-patch / 2, patch / 2), turn(0, 2 * kPi);
  for (int k = 0; k < kCount; ++k) {
    const double x = centre(rng), y = centre(rng);
    AddTriangle(scene, x, y, kSide / std::sqrt(3.0), turn(rng), -0.15 - (spread ? 1e-5 * k : 0));
  }
  return scene;
}

v1::Scene CoplanarLayersScene() {
  v1::Scene scene = FlatScene("coplanar-layers");
  std::mt19937 rng(49);
  constexpr int kShapes = 296, kLayers = 27;
  constexpr double kSide = 0.01;
  const double patch = std::sqrt(kShapes * std::sqrt(3.0) / 4 * kSide * kSide);
  std::uniform_real_distribution<double> centre(-patch / 2, patch / 2), turn(0, 2 * kPi);
  double shapes[kShapes][3];
  for (auto& s : shapes) s[0] = centre(rng), s[1] = centre(rng), s[2] = turn(rng);
  for (int layer = 0; layer < kLayers; ++layer)
    for (const auto& s : shapes)
      AddTriangle(scene, s[0], s[1], kSide / std::sqrt(3.0), s[2], -0.15);
  return scene;
}

v1::Scene StackedLayersScene(bool spread) {
  v1::Scene scene = FlatScene(spread ? "stacked-spread" : "stacked");
  std::mt19937 rng(48);
  std::uniform_real_distribution<double> centre(-0.05, 0.05), turn(0, 2 * kPi);
  double shapes[10][3];
  for (auto& s : shapes) s[0] = centre(rng), s[1] = centre(rng), s[2] = turn(rng);
  for (int layer = 0; layer < 20; ++layer)
    for (int k = 0; k < 10; ++k)
      AddTriangle(scene, shapes[k][0], shapes[k][1], 0.1, shapes[k][2],
                  -1.0 - 0.001 * (spread ? 10 * layer + k : layer));
  return scene;
}

v1::Scene CopiesScene(int copies) {
  v1::Scene scene = FlatScene("copies");
  v1::Mesh& quad = *scene.mutable_meshes(0);
  quad.set_id("quad");
  quad.set_material_id("m0");
  v1::Polygon& p = *quad.add_polygons();
  for (auto [x, y] : {std::pair{-0.5, -0.4}, {0.5, -0.4}, {0.5, 0.4}, {-0.5, 0.4}}) {
    v1::Vec3& v = *p.add_vertices();
    v.set_x(x);
    v.set_y(y);
  }
  for (int k = 0; k < copies; ++k) {
    v1::Object& o = *scene.add_objects();
    o.set_mesh_id("quad");
    o.set_name(absl::StrCat("object", k));
    o.set_material_id(absl::StrCat("m", k % kColours));
    o.mutable_transform()->mutable_translation()->set_z(-2);
  }
  return scene;
}

}  // namespace aperture::testing
