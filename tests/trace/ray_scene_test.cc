// The Embree wrapper: hits report the scene polygon (not the fan triangle), the nearest polygon
// wins, the ray segment [t_near, t_far] is honoured, and a scene far from the origin still hits.
#include "trace/ray_scene.h"

#include <gtest/gtest.h>

namespace aperture {
namespace {

ScenePolygon Hexagon(double cx, double cy, double z, double r) {
  ScenePolygon p;
  for (int k = 0; k < 6; ++k)
    p.vertices.push_back({cx + r * std::cos(k * kPi / 3), cy + r * std::sin(k * kPi / 3), z});
  p.normal = {0, 0, 1};
  return p;
}

TEST(RayScene, ReportsThePolygonNearestAlongTheRay) {
  Scene scene;
  // Polygon 1 (radius 0.5 around (0.5, 0.5) at z = -5) hangs in front of part of polygon 0.
  scene.polygons = {Hexagon(0, 0, -10, 2), Hexagon(0.5, 0.5, -5, 0.5), Hexagon(20, 0, -10, 2)};
  auto rs = RayScene::Build(scene);
  ASSERT_TRUE(rs.ok()) << rs.status();
  EXPECT_EQ((*rs)->triangles(), 12u);  // three hexagons, four fan triangles each
  const Vec3 o{0, 0, 0};
  // Through each of polygon 0's six fan triangles, below polygon 1: polygon 0 every time.
  for (int k = 0; k < 6; ++k) {
    const double a = (k + 0.5) * kPi / 3, r = k == 0 ? 0.1 : 1.5;
    EXPECT_EQ((*rs)->Intersect(o, {r * std::cos(a) / 10, r * std::sin(a) / 10, -1}, 0.01, INFINITY),
              0)
        << k;
  }
  const Vec3 d{0.1, 0.1, -1};  // through polygon 1's centre at z = -5, then polygon 0
  EXPECT_EQ((*rs)->Intersect(o, d, 0.01, INFINITY), 1);  // the near one in front
  EXPECT_EQ((*rs)->Intersect(o, d, 6, INFINITY), 0);     // t_near beyond it
  EXPECT_EQ((*rs)->Intersect(o, d, 0.01, 4), -1);        // t_far before both
  EXPECT_EQ((*rs)->Intersect(o, {2, 0, -1}, 0.01, INFINITY), 2);
  EXPECT_EQ((*rs)->Intersect(o, {0, 1, 0}, 0.01, INFINITY), -1);  // nothing above
}

TEST(RayScene, FarFromTheOriginAndEmpty) {
  Scene scene;
  scene.polygons = {Hexagon(50000, 30000, -10, 1)};
  auto rs = RayScene::Build(scene);
  ASSERT_TRUE(rs.ok());
  EXPECT_EQ((*rs)->Intersect({50000.2, 30000.1, 0}, {0, 0, -1}, 0.01, INFINITY), 0);
  EXPECT_EQ((*rs)->Intersect({50001.2, 30000, 0}, {0, 0, -1}, 0.01, INFINITY), -1);
  auto empty = RayScene::Build(Scene{});
  ASSERT_TRUE(empty.ok());
  EXPECT_EQ((*empty)->Intersect({0, 0, 0}, {0, 0, -1}, 0.01, INFINITY), -1);
}

}  // namespace
}  // namespace aperture
