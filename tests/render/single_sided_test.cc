// Single-sided materials (glTF's doubleSided false): the raster mode skips polygons seen from
// behind. A closed solid looks the same either way (its back faces were hidden), but for slivers
// along its silhouette; an open quad seen from behind disappears, and is drawn again when the
// camera goes round to its front.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "render/frame_renderer.h"
#include "scene/scene_builder.h"

namespace aperture {
namespace {

void AddQuad(v1::Mesh& mesh, std::initializer_list<std::array<double, 3>> corners) {
  v1::Polygon* p = mesh.add_polygons();
  for (const auto& c : corners) {
    v1::Vec3* v = p->add_vertices();
    v->set_x(c[0]), v->set_y(c[1]), v->set_z(c[2]);
  }
}

// A unit cube at (0, 0.5, -4), faces counter-clockwise seen from outside; or a quad at x = 2
// whose front faces +x.
v1::Scene Scene(bool single_sided, bool wall) {
  v1::Scene scene;
  v1::Material* m = scene.add_materials();
  m->set_id("m");
  m->mutable_base_color()->set_r(0.8f);
  m->mutable_base_color()->set_g(0.6f);
  m->mutable_base_color()->set_b(0.3f);
  m->set_single_sided(single_sided);
  v1::Mesh* mesh = scene.add_meshes();
  mesh->set_id("mesh");
  mesh->set_material_id("m");
  if (wall) {
    AddQuad(*mesh, {{2, 0, -3}, {2, 0, -5}, {2, 1.5, -5}, {2, 1.5, -3}});
  } else {
    const double x0 = -0.5, x1 = 0.5, y0 = 0, y1 = 1, z0 = -4.5, z1 = -3.5;
    AddQuad(*mesh, {{x0, y0, z1}, {x1, y0, z1}, {x1, y1, z1}, {x0, y1, z1}});  // +z
    AddQuad(*mesh, {{x1, y0, z0}, {x0, y0, z0}, {x0, y1, z0}, {x1, y1, z0}});  // -z
    AddQuad(*mesh, {{x1, y0, z1}, {x1, y0, z0}, {x1, y1, z0}, {x1, y1, z1}});  // +x
    AddQuad(*mesh, {{x0, y0, z0}, {x0, y0, z1}, {x0, y1, z1}, {x0, y1, z0}});  // -x
    AddQuad(*mesh, {{x0, y1, z1}, {x1, y1, z1}, {x1, y1, z0}, {x0, y1, z0}});  // +y
    AddQuad(*mesh, {{x0, y0, z0}, {x1, y0, z0}, {x1, y0, z1}, {x0, y0, z1}});  // -y
  }
  scene.add_objects()->set_mesh_id("mesh");
  return scene;
}

Image Render(bool single_sided, bool wall, const Camera& camera) {
  auto scene = BuildScene(Scene(single_sided, wall));
  EXPECT_TRUE(scene.ok()) << scene.status();
  RenderSettings settings;
  settings.width = 160;
  settings.height = 120;
  auto frame = RenderFrame(*scene, camera, settings);
  EXPECT_TRUE(frame.ok()) << frame.status();
  return frame->image;
}

// Pixels that differ from the sky.
int Covered(const Image& image, const Rgba& sky) {
  int covered = 0;
  for (const Rgba& t : image.texels()) covered += std::abs(t.r - sky.r) > 1e-3f;
  return covered;
}

double MaxDifference(const Image& a, const Image& b) {
  double worst = 0;
  for (size_t i = 0; i < a.texels().size(); ++i) {
    const Rgba &p = a.texels()[i], &q = b.texels()[i];
    worst = std::max({worst, double(std::abs(p.r - q.r)), double(std::abs(p.g - q.g)),
                      double(std::abs(p.b - q.b))});
  }
  return worst;
}

TEST(SingleSided, AClosedSolidLooksTheSameAndAQuadSeenFromBehindDisappears) {
  // From the -x side, looking along -z and a little right: the cube's outside, the wall's back.
  Camera camera;
  camera.position = {-1.5, 0.8, 0};
  camera.yaw_deg = -15;
  const Rgba sky = BuildScene(Scene(false, false))->sky;
  const Image cube_two = Render(false, false, camera), cube_one = Render(true, false, camera);
  EXPECT_GT(Covered(cube_one, sky), 300);  // the cube is there
  // The same but for slivers along the silhouette that the exact visibility leaves to the back
  // faces double-sided and to the sky single-sided (4.4e-4 measured).
  EXPECT_LT(MaxDifference(cube_two, cube_one), 2e-3);

  EXPECT_GT(Covered(Render(false, true, camera), sky), 300);  // the wall's back, double-sided
  EXPECT_EQ(Covered(Render(true, true, camera), sky), 0);     // gone single-sided

  // From the +x side the wall's front shows single-sided too, the same as double-sided.
  camera.position = {4, 0.8, 0};
  camera.yaw_deg = 25;
  const Image front_one = Render(true, true, camera);
  EXPECT_GT(Covered(front_one, sky), 300);
  EXPECT_LT(MaxDifference(front_one, Render(false, true, camera)), 1e-6);
}

}  // namespace
}  // namespace aperture
