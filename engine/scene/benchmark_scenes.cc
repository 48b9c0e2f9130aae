#include "scene/benchmark_scenes.h"

#include <cmath>
#include <random>

#include "absl/strings/str_cat.h"

namespace aperture {

v1::Scene MakeTriangleFieldScene(int count, double screen_size, uint32_t seed) {
  v1::Scene scene;
  scene.set_name(absl::StrCat("triangles-", count));
  scene.mutable_sky()->set_b(0.2f);
  scene.mutable_ambient()->set_r(0.3f);
  scene.mutable_ambient()->set_g(0.3f);
  scene.mutable_ambient()->set_b(0.3f);
  scene.mutable_sun()->mutable_direction()->set_x(0.3);
  scene.mutable_sun()->mutable_direction()->set_y(0.8);
  scene.mutable_sun()->mutable_direction()->set_z(0.5);
  scene.mutable_sun()->mutable_color()->set_r(0.8f);
  scene.mutable_sun()->mutable_color()->set_g(0.8f);
  scene.mutable_sun()->mutable_color()->set_b(0.7f);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(0, 1);
  for (int i = 0; i < 8; ++i) {
    v1::Material* m = scene.add_materials();
    m->set_id(absl::StrCat("c", i));
    m->mutable_base_color()->set_r(static_cast<float>(0.2 + 0.8 * unit(rng)));
    m->mutable_base_color()->set_g(static_cast<float>(0.2 + 0.8 * unit(rng)));
    m->mutable_base_color()->set_b(static_cast<float>(0.2 + 0.8 * unit(rng)));
  }
  v1::Mesh* mesh = scene.add_meshes();
  mesh->set_id("triangles");
  const double tan_half = std::tan(30.0 * 3.14159265358979323846 / 180.0);
  const double aspect = 1920.0 / 1080.0;
  const double pixel = 2 * tan_half / 1080;  // view-plane size of a pixel at depth 1
  for (int i = 0; i < count; ++i) {
    const double depth = 10 + 90 * unit(rng);
    const double cx = (2 * unit(rng) - 1) * tan_half * aspect * depth;
    const double cy = (2 * unit(rng) - 1) * tan_half * depth;
    const double radius = 0.5 * screen_size * pixel * depth;
    v1::Polygon* p = mesh->add_polygons();
    p->set_material_id(absl::StrCat("c", i % 8));
    const double spin = 6.283185307179586 * unit(rng);
    const double tilt_x = unit(rng) - 0.5, tilt_y = unit(rng) - 0.5;
    for (int k = 0; k < 3; ++k) {
      const double a = spin + k * 2.0943951023931953 + 0.5 * (unit(rng) - 0.5);
      const double dx = radius * std::cos(a), dy = radius * std::sin(a);
      v1::Vec3* v = p->add_vertices();
      v->set_x(cx + dx);
      v->set_y(cy + dy);
      v->set_z(-depth + tilt_x * dx +
               tilt_y * dy);  // tilted: triangles interpenetrate now and then
    }
  }
  return scene;
}

}  // namespace aperture
