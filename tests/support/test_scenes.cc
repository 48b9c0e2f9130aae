#include "support/test_scenes.h"

#include <string>

#include "absl/strings/str_cat.h"

namespace aperture::testing {

v1::Scene MakeFlatScene(const std::vector<FlatPolygon>& polygons, Rgba sky) {
  v1::Scene scene;
  scene.set_name("flat-test");
  scene.mutable_sky()->set_r(sky.r);
  scene.mutable_sky()->set_g(sky.g);
  scene.mutable_sky()->set_b(sky.b);
  v1::Mesh* mesh = scene.add_meshes();
  mesh->set_id("mesh");
  for (size_t i = 0; i < polygons.size(); ++i) {
    v1::Material* m = scene.add_materials();
    m->set_id(absl::StrCat("m", i));
    m->set_unlit(true);
    m->mutable_base_color()->set_r(polygons[i].colour.r);
    m->mutable_base_color()->set_g(polygons[i].colour.g);
    m->mutable_base_color()->set_b(polygons[i].colour.b);
    m->set_alpha_mode(polygons[i].alpha_mode);
    m->set_alpha_cutoff(polygons[i].alpha_cutoff);
    if (polygons[i].alpha_mode != v1::ALPHA_MODE_OPAQUE)
      m->set_transparency(1.0f - polygons[i].colour.a);
    v1::Polygon* p = mesh->add_polygons();
    p->set_material_id(m->id());
    for (const Vec3& v : polygons[i].vertices) {
      v1::Vec3* pv = p->add_vertices();
      pv->set_x(v.x);
      pv->set_y(v.y);
      pv->set_z(v.z);
    }
  }
  return scene;
}

v1::Scene MakeGrazingPlaneScene(double half_extent, double cx, double cz) {
  v1::Scene scene;
  scene.set_name("grazing-plane");
  v1::Texture* t = scene.add_textures();
  t->set_id("checker");
  t->mutable_checkerboard()->set_size(1024);
  t->mutable_checkerboard()->set_cells(8);
  v1::Material* m = scene.add_materials();
  m->set_id("checker");
  m->set_texture_id("checker");
  m->set_unlit(true);
  m->mutable_texture_transform()->set_repeat_u(4);
  v1::Mesh* mesh = scene.add_meshes();
  mesh->set_id("plane");
  mesh->set_material_id("checker");
  v1::Polygon* p = mesh->add_polygons();
  const double xs[4] = {cx - half_extent, cx + half_extent, cx + half_extent, cx - half_extent};
  const double zs[4] = {cz + half_extent, cz + half_extent, cz - half_extent, cz - half_extent};
  for (int i = 0; i < 4; ++i) {
    v1::Vec3* v = p->add_vertices();
    v->set_x(xs[i]);
    v->set_y(0);
    v->set_z(zs[i]);
  }
  return scene;
}

}  // namespace aperture::testing
