// Ray / sphere and ray / cylinder intersections against hit points computed by hand: the near and
// far roots (outside and inside), tangent and missing rays, the segment [t_near, t_far], a
// cylinder's finite length, its caps (capped or open), a tilted cylinder, and the Embree wrapper
// reporting curved primitives after the polygons.
#include "trace/curved_intersect.h"

#include <gtest/gtest.h>

#include "trace/ray_scene.h"

namespace aperture {
namespace {

CurvedPrimitive Sphere(const Vec3& centre, double r) {
  CurvedPrimitive c;
  c.kind = CurvedKind::kSphere;
  c.origin = centre;
  c.radius = r;
  return c;
}

// Axis +y from `base`, unless `axes` says otherwise.
CurvedPrimitive Cylinder(const Vec3& base, double r, double h, bool capped, Mat3 axes = {}) {
  CurvedPrimitive c;
  c.kind = CurvedKind::kCylinder;
  c.origin = base;
  c.radius = r;
  c.height = h;
  c.capped = capped;
  c.axes = axes;
  return c;
}

void ExpectNear(const Vec3& a, const Vec3& b, double eps = 1e-12) {
  EXPECT_NEAR(a.x, b.x, eps);
  EXPECT_NEAR(a.y, b.y, eps);
  EXPECT_NEAR(a.z, b.z, eps);
}

TEST(CurvedIntersect, SphereNearAndFarRoots) {
  const CurvedPrimitive s = Sphere({0, 0, -5}, 1);
  auto hit = IntersectCurved(s, {0, 0, 0}, {0, 0, -1}, 0.01, INFINITY);
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, 4, 1e-12);
  EXPECT_EQ(hit->part, CurvedPart::kOutside);
  ExpectNear(hit->point, {0, 0, -4});
  ExpectNear(hit->normal, {0, 0, 1});
  // An oblique ray, d = (0.1, 0, -1) (not unit): |t d - c|^2 = 1 is 1.01 t^2 - 10 t + 24 = 0; with
  // d = (0.3, 0, -1), 1.09 t^2 - 10 t + 24 = 0 has no root.
  const double a = 1.01, t0 = (10 - std::sqrt(100 - 4 * a * 24)) / (2 * a),
               t1 = (10 + std::sqrt(100 - 4 * a * 24)) / (2 * a);
  hit = IntersectCurved(s, {0, 0, 0}, {0.1, 0, -1}, 0.01, INFINITY);
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, t0, 1e-12);
  ExpectNear(hit->point, {0.1 * t0, 0, -t0});
  EXPECT_NEAR(Length(hit->point - s.origin), 1, 1e-12);
  EXPECT_FALSE(IntersectCurved(s, {0, 0, 0}, {0.3, 0, -1}, 0.01, INFINITY));
  // t_near beyond the near root: the far one, seen from inside.
  hit = IntersectCurved(s, {0, 0, 0}, {0.1, 0, -1}, t0 + 1e-9, INFINITY);
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, t1, 1e-12);
  EXPECT_EQ(hit->part, CurvedPart::kInside);
  EXPECT_FALSE(IntersectCurved(s, {0, 0, 0}, {0, 0, -1}, 0.01, 3.9));  // t_far before it
  // From the centre: the inside at t = r, any direction.
  hit = IntersectCurved(s, {0, 0, -5}, {0, 2, 0}, 0.0, INFINITY);
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, 0.5, 1e-12);
  EXPECT_EQ(hit->part, CurvedPart::kInside);
  ExpectNear(hit->point, {0, 1, -5});
  // Tangent: x = 1 grazes the sphere at (1, 0, -5).
  hit = IntersectCurved(s, {1, 0, 0}, {0, 0, -1}, 0.01, INFINITY);
  ASSERT_TRUE(hit);
  ExpectNear(hit->point, {1, 0, -5}, 1e-7);
}

TEST(CurvedIntersect, SphereFarFromTheOrigin) {
  const CurvedPrimitive s = Sphere({40000, 10, -30000}, 2);
  auto hit = IntersectCurved(s, {40000, 10, -29990}, {0, 0, -1}, 0.01, INFINITY);
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, 8, 1e-9);
  ExpectNear(hit->point, {40000, 10, -29998}, 1e-9);
}

TEST(CurvedIntersect, CylinderSideLengthAndCaps) {
  // Radius 1, from y = 0 to 2, axis through (0, 0, -5).
  const CurvedPrimitive open = Cylinder({0, 0, -5}, 1, 2, false);
  const CurvedPrimitive closed = Cylinder({0, 0, -5}, 1, 2, true);
  auto hit = IntersectCurved(open, {0, 1, 0}, {0, 0, -1}, 0.01, INFINITY);
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, 4, 1e-12);
  EXPECT_EQ(hit->part, CurvedPart::kOutside);
  ExpectNear(hit->normal, {0, 0, 1});
  // Above the top: the open one is missed, the capped one too (the ray passes over the cap).
  EXPECT_FALSE(IntersectCurved(open, {0, 2.5, 0}, {0, 0, -1}, 0.01, INFINITY));
  EXPECT_FALSE(IntersectCurved(closed, {0, 2.5, 0}, {0, 0, -1}, 0.01, INFINITY));
  // Straight down the axis from above: the top cap at y = 2 when capped, nothing when open.
  hit = IntersectCurved(closed, {0, 10, -5}, {0, -1, 0}, 0.01, INFINITY);
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, 8, 1e-12);
  EXPECT_EQ(hit->part, CurvedPart::kTopCap);
  ExpectNear(hit->normal, {0, 1, 0});
  EXPECT_FALSE(IntersectCurved(open, {0, 10, -5}, {0, -1, 0}, 0.01, INFINITY));
  // From below, slanted into the open bottom: the inside of the wall. Origin (0, -1, -5),
  // direction (0.5, 1, 0): x = 0.5 t reaches 1 at t = 2, y = 1.
  hit = IntersectCurved(open, {0, -1, -5}, {0.5, 1, 0}, 0.01, INFINITY);
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, 2, 1e-12);
  EXPECT_EQ(hit->part, CurvedPart::kInside);
  ExpectNear(hit->point, {1, 1, -5});
  // The capped one: the bottom cap first (y = 0 at t = 1, x = 0.5 inside the disc).
  hit = IntersectCurved(closed, {0, -1, -5}, {0.5, 1, 0}, 0.01, INFINITY);
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, 1, 1e-12);
  EXPECT_EQ(hit->part, CurvedPart::kBottomCap);
  ExpectNear(hit->point, {0.5, 0, -5});
  // Parallel to the axis outside the radius: never.
  EXPECT_FALSE(IntersectCurved(closed, {3, -10, -5}, {0, 1, 0}, 0.01, INFINITY));
}

TEST(CurvedIntersect, TiltedCylinder) {
  // The axis along world +x (frame y = +x): columns x' = (0, -1, 0), y' = (1, 0, 0), z' = (0, 0,
  // 1).
  Mat3 axes;
  axes.m[0][0] = 0, axes.m[0][1] = 1, axes.m[0][2] = 0;
  axes.m[1][0] = -1, axes.m[1][1] = 0, axes.m[1][2] = 0;
  axes.m[2][0] = 0, axes.m[2][1] = 0, axes.m[2][2] = 1;
  const CurvedPrimitive c = Cylinder({-2, 0, -5}, 0.5, 4, true, axes);
  auto hit = IntersectCurved(c, {1, 0, 0}, {0, 0, -1}, 0.01, INFINITY);  // over the side
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, 4.5, 1e-12);
  ExpectNear(hit->point, {1, 0, -4.5});
  EXPECT_EQ(hit->part, CurvedPart::kOutside);
  hit = IntersectCurved(c, {10, 0, -5}, {-1, 0, 0}, 0.01, INFINITY);  // into the end at x = 2
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, 8, 1e-12);
  EXPECT_EQ(hit->part, CurvedPart::kTopCap);
  EXPECT_FALSE(IntersectCurved(c, {2.5, 0, 0}, {0, 0, -1}, 0.01, INFINITY));  // past the end
  Vec3 lo, hi;
  CurvedBounds(c, &lo, &hi);
  ExpectNear(lo, {-2, -0.5, -5.5});
  ExpectNear(hi, {2, 0.5, -4.5});
}

TEST(CurvedIntersect, EmbreeReportsCurvedPrimitivesAfterPolygons) {
  Scene scene;
  ScenePolygon wall;  // z = -20, large
  wall.vertices = {{-50, -50, -20}, {50, -50, -20}, {50, 50, -20}, {-50, 50, -20}};
  wall.normal = {0, 0, 1};
  scene.polygons.push_back(wall);
  scene.curved = {Sphere({0, 0, -5}, 1), Cylinder({3, -1, -10}, 1, 2, true)};
  auto rs = RayScene::Build(scene);
  ASSERT_TRUE(rs.ok()) << rs.status();
  const Vec3 o{0, 0, 0};
  EXPECT_EQ((*rs)->Intersect(o, {0, 0, -1}, 0.01, INFINITY), 1);       // the sphere
  EXPECT_EQ((*rs)->Intersect(o, {0, 0, -1}, 6.5, INFINITY), 0);        // past it: the wall
  EXPECT_EQ((*rs)->Intersect(o, {0.3, 0, -1}, 0.01, INFINITY), 2);     // the cylinder at x = 3
  EXPECT_EQ((*rs)->Intersect(o, {0.3, 0.15, -1}, 0.01, INFINITY), 0);  // above it
  EXPECT_EQ((*rs)->Intersect(o, {0, 1, 0}, 0.01, INFINITY), -1);
  Scene only;
  only.curved = {Sphere({100, 0, 0}, 2)};
  auto alone = RayScene::Build(only);
  ASSERT_TRUE(alone.ok());
  EXPECT_EQ((*alone)->Intersect(o, {1, 0.01, 0}, 0.01, INFINITY), 0);
  EXPECT_EQ((*alone)->Intersect(o, {1, 0.03, 0}, 0.01, INFINITY), -1);
}

}  // namespace
}  // namespace aperture
