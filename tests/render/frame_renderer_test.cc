#include "render/frame_renderer.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstring>
#include <utility>

#include "scene/benchmark_scenes.h"
#include "scene/demo_scene.h"
#include "scene/scene_builder.h"
#include "support/test_scenes.h"

namespace aperture {
namespace {

bool BitIdentical(const Image& a, const Image& b) {
  return a.width() == b.width() && a.height() == b.height() &&
         std::memcmp(a.texels().data(), b.texels().data(), a.texels().size_bytes()) == 0;
}

// Every material filtered trilinear, so that no table is built on first use.
RenderSettings TrilinearSettings(int width, int height, int threads) {
  RenderSettings settings;
  settings.width = width;
  settings.height = height;
  settings.shading.override_filter = true;
  settings.shading.filter = FilterMode::kTrilinear;
  settings.threads = threads;
  return settings;
}

TEST(FrameRenderer, BitIdenticalAcrossThreadCountsAndRuns) {
  auto scene = BuildScene(MakeDemoScene());
  ASSERT_TRUE(scene.ok()) << scene.status();
  RenderSettings settings;
  settings.width = 480;
  settings.height = 270;
  for (AntiAliasing aa : {AntiAliasing::kBox2, AntiAliasing::kTent2}) {
    settings.aa = aa;
    settings.threads = 1;
    auto one = RenderFrame(*scene, DemoCamera(), settings);
    settings.threads = 2;
    auto two = RenderFrame(*scene, DemoCamera(), settings);
    auto again = RenderFrame(*scene, DemoCamera(), settings);
    ASSERT_TRUE(one.ok() && two.ok() && again.ok());
    EXPECT_TRUE(BitIdentical(one->image, two->image)) << AntiAliasingName(aa);
    EXPECT_TRUE(BitIdentical(two->image, again->image)) << AntiAliasingName(aa);
    EXPECT_GT(one->stats.mixed_leaves, 0u);
  }
}

TEST(FrameRenderer, SchedulingAndRegionsDoNotChangeAPixel) {
  // Split frames need every task partition and every region to give the very same
  // pixels as the whole frame.
  auto scene = BuildScene(MakeDemoScene());
  ASSERT_TRUE(scene.ok());
  RenderSettings settings = TrilinearSettings(320, 180, 2);
  auto cost = RenderFrame(*scene, DemoCamera(), settings);
  settings.scheduling.mode = Scheduling::kUniform;
  settings.scheduling.uniform_tile = 24;
  auto uniform = RenderFrame(*scene, DemoCamera(), settings);
  ASSERT_TRUE(cost.ok() && uniform.ok());
  EXPECT_TRUE(BitIdentical(cost->image, uniform->image));

  settings.region = {37, 81, 250, 179};
  auto region = RenderFrame(*scene, DemoCamera(), settings);
  ASSERT_TRUE(region.ok());
  ASSERT_EQ(region->image.width(), 213);
  ASSERT_EQ(region->image.height(), 98);
  bool same = true;
  for (int y = 0; y < 98; ++y)
    for (int x = 0; x < 213; ++x)
      same = same && region->image.at(x, y) == cost->image.at(37 + x, 81 + y);
  EXPECT_TRUE(same);

  settings.region = {300, 0, 330, 10};
  auto outside = RenderFrame(*scene, DemoCamera(), settings);
  ASSERT_FALSE(outside.ok());
  EXPECT_NE(outside.status().message().find("region"), std::string::npos);
}

TEST(FrameRenderer, StopRequestEndsTheFrameCancelled) {
  auto scene = BuildScene(MakeDemoScene());
  ASSERT_TRUE(scene.ok());
  RenderSettings settings;
  settings.width = 640;
  settings.height = 360;
  settings.shading.override_filter = true;
  std::atomic<int> asked{0};
  auto frame = RenderFrame(*scene, DemoCamera(), settings, [&] { return ++asked > 5; });
  ASSERT_FALSE(frame.ok());
  EXPECT_EQ(frame.status().code(), absl::StatusCode::kCancelled);
  EXPECT_GT(asked.load(), 5);
}

// The whole demo in one pixel, or in one row, is a few crowded cells: their cost must grow with
// the pieces, not their cube (which takes 10-50 s here). The bound is generous;
// aperture-render --size 1x1 prints the real figure (docs/BENCHMARKS.md).
TEST(FrameRenderer, WholeSceneInOnePixelOrRowIsQuick) {
  auto scene = BuildScene(MakeDemoScene());
  ASSERT_TRUE(scene.ok());
  for (const auto& [width, height] : {std::pair{1, 1}, std::pair{640, 1}, std::pair{64, 1}}) {
    const auto start = std::chrono::steady_clock::now();
    auto frame = RenderFrame(*scene, DemoCamera(), TrilinearSettings(width, height, 2));
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    ASSERT_TRUE(frame.ok()) << frame.status();
    EXPECT_LT(seconds, 3.0) << width << "x" << height;
    // The pixel sees the ground and the sky: neither black nor the sky alone.
    const Rgba p = frame->image.at(0, 0);
    EXPECT_GT(p.r + p.g + p.b, 0.1f);
    EXPECT_NE(p, scene->sky);
  }
}

// The stop test is asked inside a task too: a one-task frame (the whole demo in one pixel) stops.
TEST(FrameRenderer, StopRequestReachesInsideATask) {
  auto scene = BuildScene(MakeDemoScene());
  ASSERT_TRUE(scene.ok());
  std::atomic<int> asked{0};
  auto frame =
      RenderFrame(*scene, DemoCamera(), TrilinearSettings(1, 1, 1), [&] { return ++asked > 1; });
  ASSERT_FALSE(frame.ok());
  EXPECT_EQ(frame.status().code(), absl::StatusCode::kCancelled);
}

// ... and inside a mixed leaf, after each row of its cells: the top-left 64 x 64 pixels of a
// tris-100000 frame, as one uniform task, are one mixed leaf of uncrowded cells (about three
// pieces each), which asks at least once a row; asked only between tasks and leaves, it would
// ask twice and finish.
TEST(FrameRenderer, AMixedLeafAsksTheStopTestRowByRow) {
  auto scene = BuildScene(MakeTrisScene(100000));
  ASSERT_TRUE(scene.ok());
  RenderSettings settings = TrilinearSettings(1920, 1080, 1);
  settings.region = {0, 0, 64, 64};
  settings.scheduling.mode = Scheduling::kUniform;
  settings.scheduling.uniform_tile = 64;
  int asked_when_free = 0;
  auto free_frame = RenderFrame(*scene, Camera{}, settings, [&] { return ++asked_when_free < 0; });
  ASSERT_TRUE(free_frame.ok()) << free_frame.status();
  EXPECT_GE(asked_when_free, 64);
  std::atomic<int> asked{0};
  auto frame = RenderFrame(*scene, Camera{}, settings, [&] { return ++asked > 3; });
  ASSERT_FALSE(frame.ok());
  EXPECT_EQ(frame.status().code(), absl::StatusCode::kCancelled);
}

TEST(FrameRenderer, LeafSizesBelowOneAreRefusedByName) {
  auto scene = BuildScene(MakeTrisScene(10));
  ASSERT_TRUE(scene.ok());
  RenderSettings settings = TrilinearSettings(64, 64, 1);
  settings.warnock.leaf_size = 0;
  auto frame = RenderFrame(*scene, Camera{}, settings);
  ASSERT_EQ(frame.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_NE(frame.status().message().find("leaf size"), std::string::npos) << frame.status();
  settings.warnock.leaf_size = 16;
  settings.warnock.crowded_leaf_size = -3;
  frame = RenderFrame(*scene, Camera{}, settings);
  ASSERT_EQ(frame.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_NE(frame.status().message().find("crowded leaf size"), std::string::npos)
      << frame.status();
}

TEST(FrameRenderer, PrecisionFarFromTheOrigin) {
  // DESIGN.md's grazing plane as one 100 km polygon; moving the camera by 2,500 texture periods
  // (10 km along x) must leave the frame unchanged.
  auto scene = BuildScene(testing::MakeGrazingPlaneScene(50000, 5000, 0));
  ASSERT_TRUE(scene.ok()) << scene.status();
  RenderSettings settings;
  settings.width = 256;
  settings.height = 192;
  settings.shading.override_filter = true;
  settings.shading.filter = FilterMode::kTrilinear;
  Camera near_origin, far_away;
  near_origin.position = {0, 1, 0};
  near_origin.pitch_deg = -5;
  far_away = near_origin;
  far_away.position.x = 10000;
  auto a = RenderFrame(*scene, near_origin, settings);
  auto b = RenderFrame(*scene, far_away, settings);
  ASSERT_TRUE(a.ok() && b.ok());
  float worst = 0;
  double mean = 0;
  for (size_t i = 0; i < a->image.texels().size(); ++i) {
    const Rgba& p = a->image.texels()[i];
    const Rgba& q = b->image.texels()[i];
    worst = std::max({worst, std::abs(p.r - q.r), std::abs(p.g - q.g), std::abs(p.b - q.b)});
    mean += p.r;
  }
  mean /= static_cast<double>(a->image.texels().size());
  EXPECT_LE(worst, 1.0f / 256);
  EXPECT_GT(mean, 0.1);  // the checkerboard is there, not an empty frame
}

TEST(FrameRenderer, CostPlanForMoreWorkersIsFinerAndPixelIdentical) {
  // scheduling_bench replays plans made for more workers than the machine has: the plan must
  // follow plan_workers, not the threads that render it, and still give the same pixels.
  auto scene = BuildScene(MakeDemoScene());
  ASSERT_TRUE(scene.ok());
  RenderSettings settings = TrilinearSettings(480, 270, 1);
  auto own = RenderFrame(*scene, DemoCamera(), settings);
  settings.scheduling.plan_workers = 16;
  auto many = RenderFrame(*scene, DemoCamera(), settings);
  ASSERT_TRUE(own.ok() && many.ok());
  EXPECT_EQ(own->stats.concurrency, 1);
  EXPECT_GT(many->stats.tasks.size(), 2 * own->stats.tasks.size());
  EXPECT_TRUE(BitIdentical(own->image, many->image));
  EXPECT_GE(own->stats.raster_ms, own->stats.plan_ms);
  EXPECT_GT(own->stats.plan_ms, 0);

  settings.scheduling.plan_workers = -1;
  auto bad = RenderFrame(*scene, DemoCamera(), settings);
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.status().message().find("planned workers"), std::string::npos);
  settings.scheduling.plan_workers = kMaxPlanWorkers + 1;
  EXPECT_FALSE(RenderFrame(*scene, DemoCamera(), settings).ok());
}

TEST(FrameRenderer, RejectsBadSettings) {
  auto scene = BuildScene(MakeDemoScene());
  ASSERT_TRUE(scene.ok());
  RenderSettings settings;
  settings.width = 0;
  auto r = RenderFrame(*scene, DemoCamera(), settings);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message().find("image size"), std::string::npos);
  settings.width = 16385;
  settings.height = 10;
  EXPECT_FALSE(RenderFrame(*scene, DemoCamera(), settings).ok());
  settings.width = 64;
  Camera bad = DemoCamera();
  bad.position.y = NAN;
  r = RenderFrame(*scene, bad, settings);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message().find("position"), std::string::npos);
}

TEST(FrameRenderer, OffAxisFrustumShiftsTheImage) {
  // A single far square straight ahead: an off-axis frustum looking more to the right moves it
  // left in the image.
  auto scene = BuildScene(testing::MakeFlatScene(
      {{{{-1, -1, -20}, {1, -1, -20}, {1, 1, -20}, {-1, 1, -20}}, {1, 1, 1, 1}}}, {0, 0, 0, 1}));
  ASSERT_TRUE(scene.ok());
  RenderSettings settings;
  settings.width = 64;
  settings.height = 64;
  Camera symmetric;
  Camera shifted;
  shifted.off_axis = true;
  shifted.left_deg = -10, shifted.right_deg = 40, shifted.bottom_deg = -25, shifted.top_deg = 25;
  auto a = RenderFrame(*scene, symmetric, settings);
  auto b = RenderFrame(*scene, shifted, settings);
  ASSERT_TRUE(a.ok() && b.ok());
  auto centroid_x = [](const Image& img) {
    double sum = 0, weight = 0;
    for (int y = 0; y < img.height(); ++y)
      for (int x = 0; x < img.width(); ++x)
        sum += img.at(x, y).r * (x + 0.5), weight += img.at(x, y).r;
    return sum / weight;
  };
  EXPECT_NEAR(centroid_x(a->image), 32.0, 0.01);
  // tan(0) maps to (0 - tan(-10)) / (tan(40) - tan(-10)) of the width.
  const double expected =
      std::tan(Radians(10)) / (std::tan(Radians(40)) + std::tan(Radians(10))) * 64;
  EXPECT_NEAR(centroid_x(b->image), expected, 0.2);
}

}  // namespace
}  // namespace aperture
