#include "scene/scene_builder.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <set>

#include "scene/builtin_scenes.h"
#include "scene/demo_scene.h"
#include "support/test_scenes.h"

namespace aperture {
namespace {

double U(const ScenePolygon& p, const Vec3& x) { return Dot(p.mapping.su, x) + p.mapping.u0; }
double V(const ScenePolygon& p, const Vec3& x) { return Dot(p.mapping.sv, x) + p.mapping.v0; }

TEST(SceneBuilder, GroundPlaneMapsUAndVAsInDesign) {
  auto scene = BuildScene(testing::MakeGrazingPlaneScene(100));
  ASSERT_TRUE(scene.ok()) << scene.status();
  ASSERT_EQ(scene->polygons.size(), 1u);
  const ScenePolygon& p = scene->polygons[0];
  EXPECT_NEAR(U(p, {10, 0, -6}), 2.5, 1e-12);   // u = x / 4
  EXPECT_NEAR(V(p, {10, 0, -6}), -1.5, 1e-12);  // v = z / 4
}

TEST(SceneBuilder, ExplicitUvsAreReproducedAtTheVertices) {
  v1::Scene proto;
  v1::Mesh* mesh = proto.add_meshes();
  mesh->set_id("m");
  v1::Polygon* poly = mesh->add_polygons();
  const Vec3 vs[4] = {{0, 0, 0}, {2, 0, 0}, {2, 3, 1}, {0, 3, 1}};
  const Vec2 uvs[4] = {{0.1, 0.2}, {0.9, 0.2}, {0.9, 1.7}, {0.1, 1.7}};
  for (int i = 0; i < 4; ++i) {
    v1::Vec3* v = poly->add_vertices();
    v->set_x(vs[i].x), v->set_y(vs[i].y), v->set_z(vs[i].z);
    v1::Vec2* t = poly->add_uvs();
    t->set_u(uvs[i].x), t->set_v(uvs[i].y);
  }
  auto scene = BuildScene(proto);
  ASSERT_TRUE(scene.ok()) << scene.status();
  const ScenePolygon& p = scene->polygons[0];
  for (int i = 0; i < 4; ++i) {
    EXPECT_NEAR(U(p, vs[i]), uvs[i].x, 1e-12);
    EXPECT_NEAR(V(p, vs[i]), uvs[i].y, 1e-12);
  }
}

TEST(SceneBuilder, ObjectTransformsPlaceMeshes) {
  auto proto = testing::MakeFlatScene({{{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {1, 1, 1, 1}}}, {});
  v1::Object* o = proto.add_objects();
  o->set_mesh_id("mesh");
  o->mutable_transform()->mutable_translation()->set_x(10);
  o->mutable_transform()->set_yaw_deg(90);
  o->mutable_transform()->mutable_scale()->set_x(2);
  o->mutable_transform()->mutable_scale()->set_y(1);
  o->mutable_transform()->mutable_scale()->set_z(1);
  auto scene = BuildScene(proto);
  ASSERT_TRUE(scene.ok()) << scene.status();
  ASSERT_EQ(scene->polygons.size(), 1u);
  // (1, 0, 0) scaled to (2, 0, 0), yawed 90 degrees to (0, 0, -2), moved to (10, 0, -2).
  const Vec3 v = scene->polygons[0].vertices[1];
  EXPECT_NEAR(v.x, 10, 1e-12);
  EXPECT_NEAR(v.z, -2, 1e-12);
}

// A scene that reaches the builder with glTF model references unresolved (a request to the
// service, which never reads the client's files) is refused, naming the model or the object.
TEST(SceneBuilder, UnresolvedModelReferencesAreRefused) {
  v1::Scene scene;
  v1::Model* model = scene.add_models();
  model->set_id("hall");
  model->set_file("hangar.glb");
  auto built = BuildScene(scene, {});
  ASSERT_FALSE(built.ok());
  EXPECT_EQ(built.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_NE(built.status().message().find("models[0] ('hall')"), std::string::npos)
      << built.status();
  scene.clear_models();
  scene.add_objects()->set_model_id("hall");
  built = BuildScene(scene, {});
  ASSERT_FALSE(built.ok());
  EXPECT_NE(built.status().message().find("objects[0].model_id: 'hall' is not resolved"),
            std::string::npos)
      << built.status();
}

TEST(SceneBuilder, DemoSceneBuilds) {
  auto scene = BuildScene(MakeDemoScene());
  ASSERT_TRUE(scene.ok()) << scene.status();
  EXPECT_GT(scene->polygons.size(), 1000u);
  EXPECT_EQ(scene->textures.size(), 3u);
}

// A big concave polygon (a 200,000-vertex star on the ground) is triangulated in O(n log n)
// while the scene loads; ear clipping, O(n^2), would take minutes. Generous bound; the figure is
// in docs/ENGINE.md.
TEST(SceneBuilder, BigConcavePolygonLoadsQuickly) {
  v1::Scene proto;
  proto.add_materials()->set_id("m");
  v1::Mesh* mesh = proto.add_meshes();
  mesh->set_id("star");
  mesh->set_material_id("m");
  v1::Polygon* poly = mesh->add_polygons();
  const int n = 200000;
  for (int i = 0; i < n; ++i) {
    const double a = -2 * M_PI * (i + 0.5) / n, r = i % 2 == 0 ? 100 : 60 + (i % 7);
    v1::Vec3* v = poly->add_vertices();
    v->set_x(r * std::cos(a));
    v->set_z(r * std::sin(a));
  }
  const auto start = std::chrono::steady_clock::now();
  auto scene = BuildScene(proto);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  ASSERT_TRUE(scene.ok()) << scene.status();
  EXPECT_EQ(scene->polygons.size(), static_cast<size_t>(n - 2));
  double area = 0;
  for (const ScenePolygon& p : scene->polygons) {
    const Vec3 e1 = p.vertices[1] - p.vertices[0], e2 = p.vertices[2] - p.vertices[0];
    area += 0.5 * Length(Cross(e1, e2));
  }
  double expected = 0;  // the star's own area, by the shoelace formula in (x, z)
  for (int i = 0; i < n; ++i) {
    const v1::Vec3 &a = poly->vertices(i), &b = poly->vertices((i + 1) % n);
    expected += 0.5 * (a.x() * b.z() - b.x() * a.z());
  }
  EXPECT_NEAR(area, std::abs(expected), 1e-9 * std::abs(expected));
  EXPECT_LT(seconds, 10.0);
}

// The tris-N scene (the peer benchmark's): N triangles, each later one nearer, vertices
// within 12 pixels of a centre inside the 1920 x 1080 frame of the camera at the origin.
TEST(SceneBuilder, TrisSceneByNameHasItsTrianglesInPaintingOrder) {
  auto builtin = FindBuiltinScene("tris-500");
  ASSERT_TRUE(builtin.ok()) << builtin.status();
  auto scene = BuildScene(builtin->scene);
  ASSERT_TRUE(scene.ok()) << scene.status();
  ASSERT_EQ(scene->polygons.size(), 500u);
  const double pixel = 2 * std::tan(M_PI / 6) / 1080;  // at depth 1
  double previous_depth = INFINITY;
  for (const ScenePolygon& p : scene->polygons) {
    ASSERT_EQ(p.vertices.size(), 3u);
    const double depth = -p.vertices[0].z;
    EXPECT_LT(depth, previous_depth);  // later in front
    previous_depth = depth;
    Vec3 c{0, 0, 0};
    for (const Vec3& v : p.vertices) c = c + v * (1.0 / 3);
    for (const Vec3& v : p.vertices) {
      EXPECT_EQ(v.z, p.vertices[0].z);
      // Within 2 R of the centroid (each vertex is within R of the generating centre).
      EXPECT_LE(std::hypot(v.x - c.x, v.y - c.y) / (pixel * depth), 24.0 + 1e-9);
      EXPECT_LE(std::abs(v.x / (pixel * depth)), 960 + 12 + 1e-9);
      EXPECT_LE(std::abs(v.y / (pixel * depth)), 540 + 12 + 1e-9);
    }
  }
  for (const char* bad : {"tris-0", "tris-x", "tris-1000001"}) {
    auto refused = FindBuiltinScene(bad);
    ASSERT_FALSE(refused.ok()) << bad;
    EXPECT_NE(refused.status().message().find("1..1000000"), std::string::npos) << bad;
  }
}

// The slivers-N scene (the service tests' slow frame): N slivers 2 units long and 0.02 wide on
// 13 planes facing the camera, in view of the camera at the origin.
TEST(SceneBuilder, SliversSceneByNameHasItsSliversOnThirteenPlanes) {
  auto builtin = FindBuiltinScene("slivers-260");
  ASSERT_TRUE(builtin.ok()) << builtin.status();
  auto scene = BuildScene(builtin->scene);
  ASSERT_TRUE(scene.ok()) << scene.status();
  ASSERT_EQ(scene->polygons.size(), 260u);
  std::set<double> planes;
  for (const ScenePolygon& p : scene->polygons) {
    ASSERT_EQ(p.vertices.size(), 3u);
    for (const Vec3& v : p.vertices) {
      EXPECT_EQ(v.z, p.vertices[0].z);
      EXPECT_LE(std::abs(v.x), 7.1);  // centres within 6 units of the axis, half-length 1
      EXPECT_LE(std::abs(v.y), 7.1);
    }
    planes.insert(p.vertices[0].z);
    EXPECT_NEAR(std::hypot(p.vertices[1].x - p.vertices[0].x, p.vertices[1].y - p.vertices[0].y),
                2.0, 1e-9);
    EXPECT_NEAR(std::hypot(p.vertices[2].x - p.vertices[1].x, p.vertices[2].y - p.vertices[1].y),
                0.02, 1e-9);
  }
  EXPECT_EQ(planes.size(), 13u);
  EXPECT_GE(*planes.begin(), -10.0125);
  EXPECT_LE(*planes.rbegin(), -10.0);
  for (const char* bad : {"slivers-0", "slivers-", "slivers-1000001"}) {
    auto refused = FindBuiltinScene(bad);
    ASSERT_FALSE(refused.ok()) << bad;
    EXPECT_NE(refused.status().message().find("1..1000000"), std::string::npos) << bad;
    EXPECT_TRUE(NamesCountedBuiltinScene(bad)) << bad;  // its error is reported, not a file's
  }
  EXPECT_TRUE(NamesCountedBuiltinScene("tris-x"));
  EXPECT_FALSE(NamesCountedBuiltinScene("demo"));
  EXPECT_FALSE(NamesCountedBuiltinScene("slivers.json"));
}

}  // namespace
}  // namespace aperture
