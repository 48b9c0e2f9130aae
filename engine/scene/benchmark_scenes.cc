#include "scene/benchmark_scenes.h"

#include <array>
#include <cmath>
#include <random>

#include "absl/strings/str_cat.h"

namespace aperture {
namespace {

void SetColor(v1::Color* c, float r, float g, float b) {
  c->set_r(r);
  c->set_g(g);
  c->set_b(b);
}

void SetSun(v1::Scene& scene, std::array<double, 3> direction, float r, float g, float b) {
  v1::Vec3* d = scene.mutable_sun()->mutable_direction();
  d->set_x(direction[0]);
  d->set_y(direction[1]);
  d->set_z(direction[2]);
  SetColor(scene.mutable_sun()->mutable_color(), r, g, b);
}

}  // namespace

v1::Scene MakeTriangleFieldScene(int count, double screen_size, uint32_t seed) {
  v1::Scene scene;
  scene.set_name(absl::StrCat("triangles-", count));
  SetColor(scene.mutable_sky(), 0, 0, 0.2f);
  SetColor(scene.mutable_ambient(), 0.3f, 0.3f, 0.3f);
  SetSun(scene, {0.3, 0.8, 0.5}, 0.8f, 0.8f, 0.7f);
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

v1::Scene MakeTrisScene(int count, double radius_px, int width, int height, uint32_t seed) {
  v1::Scene scene;
  scene.set_name(absl::StrCat("tris-", count));
  SetColor(scene.mutable_sky(), 0, 0, 0);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(0, 1);
  constexpr int kPalette = 64;
  for (int i = 0; i < kPalette; ++i) {
    v1::Material* m = scene.add_materials();
    m->set_id(absl::StrCat("c", i));
    m->set_unlit(true);
    SetColor(m->mutable_base_color(), static_cast<float>(unit(rng)), static_cast<float>(unit(rng)),
             static_cast<float>(unit(rng)));
  }
  v1::Mesh* mesh = scene.add_meshes();
  mesh->set_id("tris");
  const double tan_half = std::tan(30.0 * 3.14159265358979323846 / 180.0);
  const double pixel = 2 * tan_half / height;  // view-plane size of a pixel at depth 1
  for (int i = 0; i < count; ++i) {
    const double depth = 100 - 90 * (i + 0.5) / count;  // later triangles nearer
    const double cx = (unit(rng) - 0.5) * width, cy = (unit(rng) - 0.5) * height;  // pixels
    v1::Polygon* p = mesh->add_polygons();
    p->set_material_id(absl::StrCat("c", static_cast<int>(unit(rng) * kPalette) % kPalette));
    for (int k = 0; k < 3; ++k) {
      // A vertex uniform in the disc of radius_px around the centre.
      const double r = radius_px * std::sqrt(unit(rng)), a = 6.283185307179586 * unit(rng);
      v1::Vec3* v = p->add_vertices();
      v->set_x((cx + r * std::cos(a)) * pixel * depth);
      v->set_y(-(cy + r * std::sin(a)) * pixel * depth);
      v->set_z(-depth);
    }
  }
  return scene;
}

v1::Scene MakeSliversScene(int count) {
  v1::Scene scene;
  scene.set_name(absl::StrCat("slivers-", count));
  for (int m = 0; m < 2; ++m) {
    v1::Material* material = scene.add_materials();
    material->set_id(m == 0 ? "orange" : "blue");
    material->set_unlit(true);
    SetColor(material->mutable_base_color(), m == 0 ? 1.0f : 0.1f, 0.5f, m == 0 ? 0.2f : 0.9f);
  }
  v1::Mesh* mesh = scene.add_meshes();
  mesh->set_id("slivers");
  for (int i = 0; i < count; ++i) {
    const double angle = 3.14159265358979323846 * i / count * 7.3;
    // Centres spread over the view by a low-discrepancy (golden ratio) sequence.
    const double cx = 12 * std::fmod(i * 0.6180339887, 1.0) - 6;
    const double cy = 12 * std::fmod(i * 0.7548776662, 1.0) - 6;
    const double dx = std::cos(angle), dy = std::sin(angle);
    const double nx = -0.02 * std::sin(angle), ny = 0.02 * std::cos(angle);
    v1::Polygon* polygon = mesh->add_polygons();
    polygon->set_material_id(i % 2 ? "blue" : "orange");
    for (const auto& [x, y] :
         {std::pair{cx - dx, cy - dy}, {cx + dx, cy + dy}, {cx + dx + nx, cy + dy + ny}}) {
      v1::Vec3* vertex = polygon->add_vertices();
      vertex->set_x(x);
      vertex->set_y(y);
      vertex->set_z(-10 - 0.001 * (i % 13));
    }
  }
  scene.add_objects()->set_mesh_id("slivers");
  return scene;
}

v1::Scene MakeSkewedCityScene(uint32_t seed) {
  v1::Scene scene;
  scene.set_name("skewed-city");
  SetColor(scene.mutable_sky(), 0.5f, 0.65f, 0.9f);
  SetColor(scene.mutable_ambient(), 0.35f, 0.35f, 0.4f);
  SetSun(scene, {0.4, 0.9, 0.3}, 0.8f, 0.8f, 0.75f);
  v1::Material* m = scene.add_materials();
  m->set_id("building");
  SetColor(m->mutable_base_color(), 0.7f, 0.65f, 0.6f);
  v1::Mesh* mesh = scene.add_meshes();
  mesh->set_id("city");
  mesh->set_material_id("building");
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> height(1, 9);
  auto quad = [&](std::initializer_list<std::array<double, 3>> pts) {
    v1::Polygon* p = mesh->add_polygons();
    for (const auto& q : pts) {
      v1::Vec3* v = p->add_vertices();
      v->set_x(q[0]);
      v->set_y(q[1]);
      v->set_z(q[2]);
    }
  };
  const double ground = -24;
  for (int i = 0; i < 30; ++i) {
    for (int j = 0; j < 30; ++j) {
      const double x0 = -60 + i * 1.6, z0 = -80 + j * 1.6, x1 = x0 + 1.1, z1 = z0 + 1.1;
      const double y0 = ground, y1 = ground + height(rng);
      quad({{x0, y0, z1}, {x1, y0, z1}, {x1, y1, z1}, {x0, y1, z1}});
      quad({{x1, y0, z0}, {x0, y0, z0}, {x0, y1, z0}, {x1, y1, z0}});
      quad({{x1, y0, z1}, {x1, y0, z0}, {x1, y1, z0}, {x1, y1, z1}});
      quad({{x0, y0, z0}, {x0, y0, z1}, {x0, y1, z1}, {x0, y1, z0}});
      quad({{x0, y1, z1}, {x1, y1, z1}, {x1, y1, z0}, {x0, y1, z0}});
    }
  }
  return scene;
}

}  // namespace aperture
