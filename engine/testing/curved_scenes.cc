#include "testing/curved_scenes.h"

namespace aperture {
namespace {

void Set(v1::Vec3* v, double x, double y, double z) {
  v->set_x(x);
  v->set_y(y);
  v->set_z(z);
}

void Set(v1::Color* c, float r, float g, float b) {
  c->set_r(r);
  c->set_g(g);
  c->set_b(b);
}

}  // namespace

CurvedTestScene MakeCurvedTestScene(CurvedSceneKind kind, int checker_size) {
  CurvedTestScene out;
  v1::Scene& s = out.scene;
  v1::Texture* t = s.add_textures();
  t->set_id("checker");
  t->mutable_checkerboard()->set_size(static_cast<uint32_t>(checker_size));
  t->mutable_checkerboard()->set_cells(8);
  Set(s.mutable_sky(), 0, 0, 0);
  v1::Material* m = s.add_materials();
  m->set_id("checks");
  m->set_texture_id("checker");
  if (kind == CurvedSceneKind::kSphere) {
    // 64 checks around, 32 from pole to pole: about 1.5 pixels each at the centre of a 48-pixel
    // image, fewer towards the limb. Unlit; the pole tilted towards the camera.
    s.set_name("curved-sphere");
    m->set_unlit(true);
    m->mutable_texture_transform()->set_repeat_u(1.0 / 8);
    m->mutable_texture_transform()->set_repeat_v(1.0 / 4);
    v1::Sphere* sp = s.add_spheres();
    Set(sp->mutable_center(), 0, 0, -3);
    sp->set_radius(1.3);
    Set(sp->mutable_pole(), 0, 1, 0.4);
    sp->set_material_id("checks");
    out.camera.position = {0, 0, 0};
  } else {
    // A capped cylinder seen from above at 24 degrees, lit by a sun from the upper left: 64
    // checks around the side, 8 up it; the same transform gives the caps 64 x 8 across.
    s.set_name("curved-cylinder");
    Set(s.mutable_ambient(), 0.35f, 0.35f, 0.35f);
    Set(s.mutable_sun()->mutable_direction(), -0.5, 1, 0.6);
    Set(s.mutable_sun()->mutable_color(), 0.8f, 0.8f, 0.75f);
    m->mutable_texture_transform()->set_repeat_u(1.0 / 8);
    m->mutable_texture_transform()->set_repeat_v(1);
    v1::Cylinder* c = s.add_cylinders();
    Set(c->mutable_base(), 0, -1.2, -4);
    Set(c->mutable_top(), 0, 0.6, -4);
    c->set_radius(1);
    c->set_capped(true);
    c->set_material_id("checks");
    out.camera.position = {0, 1.5, 0};
    out.camera.pitch_deg = -24;
  }
  out.camera.vertical_fov_deg = 60;
  out.camera.near = 0.01;
  return out;
}

}  // namespace aperture
