#include "support/runway_lights_scene.h"

#include <cmath>

namespace aperture::testing {
namespace {

constexpr double kRunwayLength = 3000, kRunwayHalfWidth = 22.5;

void SetVec(v1::Vec3* v, double x, double y, double z) {
  v->set_x(x);
  v->set_y(y);
  v->set_z(z);
}

void SetColor(v1::Color* c, float r, float g, float b) {
  c->set_r(r);
  c->set_g(g);
  c->set_b(b);
}

struct RowColor {
  float r, g, b;
};
// Incandescent white, aviation red and green (linear).
constexpr RowColor kWhite{1.0f, 0.93f, 0.8f}, kRed{1.0f, 0.08f, 0.04f}, kGreen{0.1f, 1.0f, 0.5f};

// A row from (x0, y, z0) to (x1, y, z1): `count` lights, or every `spacing` metres when count is 0.
void AddRow(v1::Scene& scene, const std::string& name, double x0, double z0, double x1, double z1,
            double y, int count, double spacing, RowColor color, double intensity_cd) {
  v1::LightRow& row = *scene.add_light_rows();
  SetVec(row.mutable_start(), x0, y, z0);
  SetVec(row.mutable_end(), x1, y, z1);
  if (count > 0) {
    row.set_count(count);
  } else {
    row.set_spacing_m(spacing);
  }
  v1::LightPoint& light = *row.mutable_light();
  SetColor(light.mutable_color(), color.r, color.g, color.b);
  light.set_intensity_cd(intensity_cd);
  light.set_group(name);
}

void AddQuad(v1::Scene& scene, const std::string& id, double x0, double z0, double x1, double z1,
             float grey) {
  v1::Material& material = *scene.add_materials();
  material.set_id(id);
  material.set_unlit(true);
  SetColor(material.mutable_base_color(), grey, grey, grey * 1.1f);
  v1::Mesh& mesh = *scene.add_meshes();
  mesh.set_id(id);
  mesh.set_material_id(id);
  v1::Polygon& quad = *mesh.add_polygons();
  // Counter-clockwise seen from above (+y).
  SetVec(quad.add_vertices(), x0, 0, z0);
  SetVec(quad.add_vertices(), x1, 0, z0);
  SetVec(quad.add_vertices(), x1, 0, z1);
  SetVec(quad.add_vertices(), x0, 0, z1);
}

}  // namespace

v1::Scene MakeRunwayLightsScene(const RunwayLightsOptions& options) {
  v1::Scene scene;
  scene.set_name("runway lights");
  // The ground, then the runway drawn over it (coplanar: the later is seen).
  AddQuad(scene, "ground", -4000, 4000, 4000, -8000, 0.01f);
  AddQuad(scene, "runway", -kRunwayHalfWidth, 0, kRunwayHalfWidth, -kRunwayLength, 0.025f);
  // Elevated lights stand 0.3 m above the surface, inset centre line lights 0.05 m: the view ray
  // meets a light before the ground under it, so the ground never hides one.
  const double edge_x = kRunwayHalfWidth + 1;
  AddRow(scene, "edge-left", -edge_x, 0, -edge_x, -kRunwayLength, 0.3, 0, 60, kWhite, 2500);
  AddRow(scene, "edge-right", edge_x, 0, edge_x, -kRunwayLength, 0.3, 0, 60, kWhite, 2500);
  AddRow(scene, "centre", 0, -15, 0, -2685, 0.05, 0, 30, kWhite, 2000);
  AddRow(scene, "centre-end", 0, -2715, 0, -2985, 0.05, 0, 30, kRed, 2000);
  AddRow(scene, "threshold", -21, 1, 21, 1, 0.3, 15, 0, kGreen, 3000);
  AddRow(scene, "runway-end", -21, -kRunwayLength - 1, 21, -kRunwayLength - 1, 0.3, 8, 0, kRed,
         1500);
  AddRow(scene, "approach", 0, 30, 0, 900, 0.3, 0, 30, kWhite, 5000);
  AddRow(scene, "crossbar", -15, 300, 15, 300, 0.3, 11, 0, kWhite, 5000);
  scene.mutable_light_settings()->set_exposure(options.exposure);
  return scene;
}

double GlidePath::DistanceAt(double time_s) const {
  return start_distance_m - speed_mps * std::cos(Radians(slope_deg)) * time_s;
}

Camera GlidePath::At(double time_s) const {
  const double distance = DistanceAt(time_s);
  // The direction flown, horizontal: the camera's forward (-z) turned by the heading.
  const Vec3 ahead{-std::sin(Radians(heading_deg)), 0, -std::cos(Radians(heading_deg))};
  Camera camera;
  camera.position = aim - ahead * distance + Vec3{0, distance * std::tan(Radians(slope_deg)), 0};
  camera.yaw_deg = heading_deg;
  camera.pitch_deg = -slope_deg;
  camera.vertical_fov_deg = 60;
  return camera;
}

}  // namespace aperture::testing
