// ProjectScene projects chunks of the scene in parallel: the geometry must not depend on the
// threads, and every polygon must come out once, in scene order, or be culled for a reason.
#include "raster/projection.h"

#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <vector>

#include "scene/benchmark_scenes.h"
#include "scene/scene_builder.h"
#include "support/reference_render.h"

namespace aperture {
namespace {

bool SameLinear(const ScreenLinear& a, const ScreenLinear& b) {
  return a.a == b.a && a.b == b.b && a.c == b.c;
}

bool SamePolygon(const ScreenPolygon& a, const ScreenPolygon& b) {
  if (a.vertices.size() != b.vertices.size()) return false;
  for (size_t i = 0; i < a.vertices.size(); ++i)
    if (a.vertices[i].x != b.vertices[i].x || a.vertices[i].y != b.vertices[i].y) return false;
  return a.scene_polygon == b.scene_polygon && a.material == b.material &&
         SameLinear(a.inv_depth, b.inv_depth) && SameLinear(a.u_num, b.u_num) &&
         SameLinear(a.v_num, b.v_num) && a.light == b.light && a.min_x == b.min_x &&
         a.max_y == b.max_y;
}

TEST(ProjectScene, TheSameGeometryOnOneThreadAndOnTwoInSceneOrder) {
  // More than one batch of chunks' worth of triangles, a frame narrower than the scene's (the right
  // part of the scene is culled, so chunks keep different counts).
  auto scene = BuildScene(MakeTrisScene(300000));
  ASSERT_TRUE(scene.ok()) << scene.status();
  const Camera camera = testing::OriginCamera();
  auto project = [&](int threads) {
    tbb::task_arena arena(threads);
    return arena.execute([&] { return ProjectScene(*scene, camera, 1000, 1080, 2); });
  };
  const FrameGeometry one = project(1), two = project(2);
  ASSERT_EQ(one.polygons.size(), two.polygons.size());
  EXPECT_GT(one.polygons.size(), 100000u);
  EXPECT_LT(one.polygons.size(), 300000u);  // some culled
  for (size_t i = 0; i < one.polygons.size(); ++i) {
    ASSERT_TRUE(SamePolygon(one.polygons[i], two.polygons[i])) << i;
    if (i > 0) {
      ASSERT_LT(one.polygons[i - 1].scene_polygon, one.polygons[i].scene_polygon) << i;
    }
  }
}

}  // namespace
}  // namespace aperture
