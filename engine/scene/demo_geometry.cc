#include "scene/demo_geometry.h"

#include <cmath>
#include <string>

#include "scene/demo_scene.h"
#include "texture/procedural.h"

namespace aperture::demo {

void SetColor(v1::Color* c, float r, float g, float b) {
  c->set_r(r);
  c->set_g(g);
  c->set_b(b);
}

v1::Polygon* AddPolygon(v1::Mesh* mesh, std::initializer_list<Vec3> vertices) {
  v1::Polygon* p = mesh->add_polygons();
  for (const Vec3& v : vertices) {
    v1::Vec3* pv = p->add_vertices();
    pv->set_x(v.x);
    pv->set_y(v.y);
    pv->set_z(v.z);
  }
  return p;
}

// A horizontal rectangle at height y, counter-clockwise seen from above.
void AddFlatRect(v1::Mesh* mesh, double x0, double z0, double x1, double z1, double y) {
  AddPolygon(mesh, {{x0, y, z1}, {x1, y, z1}, {x1, y, z0}, {x0, y, z0}});
}

// A closed box on the ground without its bottom face.
void AddBox(v1::Mesh* mesh, double x0, double z0, double x1, double z1, double height) {
  const double y = height;
  AddPolygon(mesh, {{x0, 0, z1}, {x1, 0, z1}, {x1, y, z1}, {x0, y, z1}});  // +z
  AddPolygon(mesh, {{x1, 0, z0}, {x0, 0, z0}, {x0, y, z0}, {x1, y, z0}});  // -z
  AddPolygon(mesh, {{x1, 0, z1}, {x1, 0, z0}, {x1, y, z0}, {x1, y, z1}});  // +x
  AddPolygon(mesh, {{x0, 0, z0}, {x0, 0, z1}, {x0, y, z1}, {x0, y, z0}});  // -x
  AddPolygon(mesh, {{x0, y, z1}, {x1, y, z1}, {x1, y, z0}, {x0, y, z0}});  // roof
}

// A vertical cylinder of `sides` facets with a flat top.
void AddTank(v1::Mesh* mesh, double cx, double cz, double radius, double height, int sides) {
  v1::Polygon* top = mesh->add_polygons();
  for (int i = 0; i < sides; ++i) {
    const double a0 = 2 * kPi * i / sides, a1 = 2 * kPi * (i + 1) / sides;
    const Vec3 p0{cx + radius * std::cos(a0), 0, cz - radius * std::sin(a0)};
    const Vec3 p1{cx + radius * std::cos(a1), 0, cz - radius * std::sin(a1)};
    AddPolygon(mesh, {p0, p1, {p1.x, height, p1.z}, {p0.x, height, p0.z}});
    v1::Vec3* v = top->add_vertices();
    v->set_x(p0.x);
    v->set_y(height);
    v->set_z(p0.z);
  }
}

// An axis-aligned box [lo, hi], every face seen from outside counter-clockwise, except the faces
// in `skip` (one that lies on another box's face would make coplanar overlapping polygons).
void AddSolidBox(v1::Mesh* mesh, const Vec3& lo, const Vec3& hi, unsigned skip) {
  const double x0 = lo.x, y0 = lo.y, z0 = lo.z, x1 = hi.x, y1 = hi.y, z1 = hi.z;
  if (!(skip & kPlusZ)) AddPolygon(mesh, {{x0, y0, z1}, {x1, y0, z1}, {x1, y1, z1}, {x0, y1, z1}});
  if (!(skip & kMinusZ)) AddPolygon(mesh, {{x1, y0, z0}, {x0, y0, z0}, {x0, y1, z0}, {x1, y1, z0}});
  if (!(skip & kPlusX)) AddPolygon(mesh, {{x1, y0, z1}, {x1, y0, z0}, {x1, y1, z0}, {x1, y1, z1}});
  if (!(skip & kMinusX)) AddPolygon(mesh, {{x0, y0, z0}, {x0, y0, z1}, {x0, y1, z1}, {x0, y1, z0}});
  if (!(skip & kTop)) AddPolygon(mesh, {{x0, y1, z1}, {x1, y1, z1}, {x1, y1, z0}, {x0, y1, z0}});
  if (!(skip & kBottom)) AddPolygon(mesh, {{x0, y0, z0}, {x1, y0, z0}, {x1, y0, z1}, {x0, y0, z1}});
}

// A twin-jet the size of an A320 (38 m long, 34 m span) in its own frame: the nose towards -z
// (where yaw 0 looks), the wheels on y = 0, the centre of the fuselage at x = z = 0. Its parts
// touch but never pass through each other: interpenetrating pieces make the exact visibility of
// a cell cost more (seed 002's depth-equality lines).
void AddAircraft(v1::Mesh* mesh) {
  AddSolidBox(mesh, {-2, 1.2, -19}, {2, 5.2, 19});          // fuselage
  AddSolidBox(mesh, {-17, 2.4, -3}, {-2, 2.8, 3}, kPlusX);  // wings, from its sides
  AddSolidBox(mesh, {2, 2.4, -3}, {17, 2.8, 3}, kMinusX);
  AddSolidBox(mesh, {-6, 4.6, 14}, {-2, 4.9, 18}, kPlusX);  // tailplane
  AddSolidBox(mesh, {2, 4.6, 14}, {6, 4.9, 18}, kMinusX);
  AddSolidBox(mesh, {-0.25, 5.2, 13}, {0.25, 12, 19}, kBottom);  // fin, on its top
  AddSolidBox(mesh, {-9, 1.0, -4}, {-7, 2.3, 0});                // engines, under the wings
  AddSolidBox(mesh, {7, 1.0, -4}, {9, 2.3, 0});
  for (const Vec3& at : {Vec3{0, 0, -14}, Vec3{-3, 0, 1}, Vec3{3, 0, 1}})  // gear legs
    AddSolidBox(mesh, {at.x - 0.3, 0, at.z - 0.3}, {at.x + 0.3, 1.15, at.z + 0.3});
}

void SetDemoWeather(v1::Scene& scene) {
  SetColor(scene.mutable_sky(), 0.50f, 0.66f, 0.90f);
  SetColor(scene.mutable_ambient(), 0.35f, 0.38f, 0.45f);
  scene.mutable_sun()->mutable_direction()->set_x(0.45);
  scene.mutable_sun()->mutable_direction()->set_y(0.8);
  scene.mutable_sun()->mutable_direction()->set_z(0.35);
  SetColor(scene.mutable_sun()->mutable_color(), 0.95f, 0.9f, 0.8f);
  SetColor(scene.mutable_fog()->mutable_color(), 0.62f, 0.70f, 0.82f);
  scene.mutable_fog()->set_density(1.0 / 9000.0);
}

void AddAircraftAndObjects(v1::Scene& scene) {
  v1::Mesh* aircraft = scene.add_meshes();
  aircraft->set_id("aircraft");
  aircraft->set_material_id("livery");
  AddAircraft(aircraft);
  for (const v1::Mesh& mesh : scene.meshes()) {
    v1::Object* object = scene.add_objects();
    object->set_mesh_id(mesh.id());
    if (mesh.id() != "aircraft") continue;
    object->set_name(kDemoAircraft);
    *object->mutable_transform() = DemoAircraftAt(0);
  }
}

v1::Material* AddMaterial(v1::Scene& scene, const char* id, float r, float g, float b,
                          const char* texture, double repeat) {
  v1::Material* m = scene.add_materials();
  m->set_id(id);
  SetColor(m->mutable_base_color(), r, g, b);
  if (texture != nullptr) {
    m->set_texture_id(texture);
    m->mutable_texture_transform()->set_repeat_u(repeat);
    // seed 000's prefiltered table: sharp at grazing angles (built once per texture, kept in the
    // shared store by the server).
    m->set_filter(v1::TEXTURE_FILTER_ANISO);
  }
  return m;
}

void AddEncodedTexture(v1::Scene& scene, const char* id, const Image& image) {
  v1::Texture* t = scene.add_textures();
  t->set_id(id);
  // Noise hardly compresses: the fastest level, since every process that builds the demo (a
  // one-frame job, a server's LoadScene) encodes it and decodes it again.
  auto png = EncodePng(image, /*zlib_level=*/1);
  if (png.ok()) t->set_encoded(std::string(png->begin(), png->end()));
}

}  // namespace aperture::demo
