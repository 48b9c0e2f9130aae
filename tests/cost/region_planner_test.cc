// Splitting a frame into K regions of equal predicted cost.
#include "cost/region_planner.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "cost/task_planner.h"
#include "render/frame_regions.h"
#include "scene/builtin_scenes.h"
#include "scene/scene_builder.h"

namespace aperture {
namespace {

ScreenPolygon Square(double x0, double y0, double x1, double y1) {
  ScreenPolygon p;
  p.vertices = {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
  p.Finalize();
  return p;
}

void ExpectBandsTileTheFrame(const std::vector<FrameRegion>& regions, int width, int height,
                             size_t k) {
  ASSERT_EQ(regions.size(), k);
  int y = 0;
  for (const FrameRegion& r : regions) {
    EXPECT_EQ(r.rect.x0, 0);
    EXPECT_EQ(r.rect.x1, width);
    EXPECT_EQ(r.rect.y0, y) << "bands must follow each other without gap or overlap";
    EXPECT_GT(r.rect.y1, r.rect.y0) << "every band holds at least one row";
    y = r.rect.y1;
  }
  EXPECT_EQ(y, height);
}

TEST(RegionPlanner, AllTheWorkInTheTopQuarterPutsTheCutsThere) {
  FrameGeometry g;
  g.width = 256;
  g.height = 256;
  // Many small squares in rows 0..63: nearly all the predicted cost lies there.
  for (int i = 0; i < 16; ++i)
    for (int j = 0; j < 4; ++j)
      g.polygons.push_back(Square(16 * i + 2, 16 * j + 2, 16 * i + 12, 16 * j + 12));
  const auto regions = PlanFrameRegions(g, ShapeOf(AntiAliasing::kBox2), 2, CostModel{});
  ExpectBandsTileTheFrame(regions, 256, 256, 2);
  EXPECT_LT(regions[0].rect.y1, 64) << "the first band ends inside the busy quarter";
}

TEST(RegionPlanner, TheBandsShareThePredictedCostOfTheUniformPlan) {
  FrameGeometry g;
  g.width = 200;
  g.height = 120;
  g.polygons = {Square(10, 10, 190, 40), Square(30, 60, 60, 110), Square(100, 50, 180, 70)};
  const CostModel model;
  SchedulingOptions options;
  options.mode = Scheduling::kUniform;
  options.uniform_tile = 16;
  options.predict_uniform = true;
  options.model = model;  // not the machine's stored model: the same constants on both sides
  double total = 0;
  for (const TaskWindow& t :
       PlanTasks(g, ShapeOf(AntiAliasing::kBox2), PixelRect{0, 0, 200, 120}, options, 1))
    total += t.predicted_us;
  for (int k : {1, 2, 3, 7, 120}) {
    const auto regions = PlanFrameRegions(g, ShapeOf(AntiAliasing::kBox2), k, model);
    ExpectBandsTileTheFrame(regions, 200, 120, static_cast<size_t>(k));
    double sum = 0;
    for (const FrameRegion& r : regions) sum += r.predicted_us;
    EXPECT_NEAR(sum, total, 1e-6 * total) << "k = " << k;
  }
}

// On the real scenes the bands' predicted costs are close to equal (a band is whole rows, so a
// row's cost is the granularity).
TEST(RegionPlanner, DemoAndSkewedScenesSplitIntoNearlyEqualPredictedCosts) {
  for (const char* name : {"demo", "skewed"}) {
    auto builtin = FindBuiltinScene(name);
    ASSERT_TRUE(builtin.ok());
    auto scene = BuildScene(builtin->scene);
    ASSERT_TRUE(scene.ok());
    RenderSettings settings;
    settings.width = 960;
    settings.height = 540;
    for (int k : {2, 4}) {
      auto regions = PlanRegions(*scene, builtin->camera, settings, k);
      ASSERT_TRUE(regions.ok()) << regions.status();
      ExpectBandsTileTheFrame(*regions, 960, 540, static_cast<size_t>(k));
      double most = 0, sum = 0;
      for (const FrameRegion& r : *regions) {
        most = std::max(most, r.predicted_us);
        sum += r.predicted_us;
      }
      EXPECT_LT(most / (sum / k), 1.05) << name << ", k = " << k;
    }
  }
}

TEST(RegionPlanner, TheNumberOfRegionsIsChecked) {
  auto builtin = FindBuiltinScene("demo");
  ASSERT_TRUE(builtin.ok());
  auto scene = BuildScene(builtin->scene);
  ASSERT_TRUE(scene.ok());
  RenderSettings settings;
  settings.width = 64;
  settings.height = 48;
  EXPECT_EQ(PlanRegions(*scene, builtin->camera, settings, 0).status().code(),
            absl::StatusCode::kInvalidArgument);
  auto too_many = PlanRegions(*scene, builtin->camera, settings, 49);
  EXPECT_EQ(too_many.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_NE(too_many.status().message().find("regions: 49 is not in 1..48"), std::string::npos)
      << too_many.status();
  EXPECT_TRUE(PlanRegions(*scene, builtin->camera, settings, 48).ok());
}

}  // namespace
}  // namespace aperture
