// The one frame entry: a raster job renders with the raster renderer and never asks for the
// traced scene, a raytraced one asks its source once (or builds its own), and both give a flat
// unlit square its colour and the sky elsewhere; a source's error and a stop are the frame's.
#include "frame/render_frame_job.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "scene/scene_builder.h"
#include "support/test_scenes.h"

namespace aperture {
namespace {

using ::testing::HasSubstr;

constexpr Rgba kSquare{0.25f, 0.5f, 0.75f, 1};
constexpr Rgba kSky{0.0625f, 0.125f, 0.1875f, 1};

// A square of side 2 at distance 5 straight ahead of a camera at the origin looking along -z:
// with a 60 degree vertical field of view it spans tan^-1(1/5) / tan(30 deg) = 34 % of the
// frame's height about the centre, so the centre pixel is the square's and the corners sky.
std::shared_ptr<const Scene> SquareScene() {
  auto scene = BuildScene(testing::MakeFlatScene(
      {{{{-1, -1, -5}, {1, -1, -5}, {1, 1, -5}, {-1, 1, -5}}, kSquare}}, kSky));
  EXPECT_TRUE(scene.ok()) << scene.status();
  return std::make_shared<const Scene>(*std::move(scene));
}

FrameJob Job(bool raytrace) {
  FrameJob job;
  job.camera = Camera{.position = {0, 0, 0}};
  job.settings.width = 48;
  job.settings.height = 32;
  job.settings.threads = 2;
  job.mode.raytrace = raytrace;
  return job;
}

void ExpectColour(const Rgba& got, const Rgba& want) {
  EXPECT_NEAR(got.r, want.r, 1e-5);
  EXPECT_NEAR(got.g, want.g, 1e-5);
  EXPECT_NEAR(got.b, want.b, 1e-5);
  EXPECT_NEAR(got.a, 1, 1e-5);
}

void ExpectSquareOnSky(const Image& image) {
  ASSERT_EQ(image.width(), 48);
  ASSERT_EQ(image.height(), 32);
  ExpectColour(image.at(24, 16), kSquare);
  ExpectColour(image.at(23, 15), kSquare);
  ExpectColour(image.at(0, 0), kSky);
  ExpectColour(image.at(47, 31), kSky);
}

TEST(RenderFrameJob, ARasterJobNeverAsksForTheTracedScene) {
  const auto scene = SquareScene();
  int asked = 0;
  const TracedSceneSource source = [&]() -> absl::StatusOr<std::shared_ptr<const TracedScene>> {
    ++asked;
    return absl::InternalError("not wanted");
  };
  auto frame = RenderFrameJob(*scene, Job(false), source);
  ASSERT_TRUE(frame.ok()) << frame.status();
  EXPECT_EQ(asked, 0);
  ExpectSquareOnSky(frame->image);
  EXPECT_EQ(FrameJobModeName(Job(false)), std::string("raster"));
}

TEST(RenderFrameJob, ARaytracedJobAsksItsSourceOnce) {
  const auto scene = SquareScene();
  auto built = TracedScene::Build(*scene);
  ASSERT_TRUE(built.ok()) << built.status();
  const std::shared_ptr<const TracedScene> traced = std::move(*built);
  int asked = 0;
  const TracedSceneSource source = [&]() -> absl::StatusOr<std::shared_ptr<const TracedScene>> {
    ++asked;
    return traced;
  };
  TraceStats stats;
  auto frame = RenderFrameJob(*scene, Job(true), source, {}, &stats);
  ASSERT_TRUE(frame.ok()) << frame.status();
  EXPECT_EQ(asked, 1);
  EXPECT_EQ(stats.corner_rays, size_t{49 * 33});  // (W + 1) x (H + 1) pixel corners
  ExpectSquareOnSky(frame->image);
  EXPECT_EQ(FrameJobModeName(Job(true)), std::string("raytrace"));
}

TEST(RenderFrameJob, ARaytracedJobWithoutASourceBuildsItsOwn) {
  const auto scene = SquareScene();
  auto frame = RenderFrameJob(*scene, Job(true));
  ASSERT_TRUE(frame.ok()) << frame.status();
  ExpectSquareOnSky(frame->image);
}

TEST(RenderFrameJob, TheSourcesErrorIsTheFrames) {
  const auto scene = SquareScene();
  const TracedSceneSource refused = []() -> absl::StatusOr<std::shared_ptr<const TracedScene>> {
    return absl::ResourceExhaustedError("tables above the budget");
  };
  auto frame = RenderFrameJob(*scene, Job(true), refused);
  ASSERT_FALSE(frame.ok());
  EXPECT_EQ(frame.status().code(), absl::StatusCode::kResourceExhausted);
  EXPECT_THAT(frame.status().message(), HasSubstr("tables above the budget"));
}

TEST(RenderFrameJob, AStoppedFrameIsCancelledInEitherMode) {
  const auto scene = SquareScene();
  for (bool raytrace : {false, true}) {
    auto frame = RenderFrameJob(*scene, Job(raytrace), {}, [] { return true; });
    ASSERT_FALSE(frame.ok()) << "raytrace " << raytrace;
    EXPECT_EQ(frame.status().code(), absl::StatusCode::kCancelled) << frame.status();
  }
}

TEST(RenderFrameJob, TheRegionIsRenderedAndNamedInTheHeader) {
  const auto scene = SquareScene();
  for (bool raytrace : {false, true}) {
    FrameJob job = Job(raytrace);
    job.settings.region = {20, 12, 30, 20};
    auto frame = RenderFrameJob(*scene, job);
    ASSERT_TRUE(frame.ok()) << frame.status();
    ASSERT_EQ(frame->image.width(), 10);
    ASSERT_EQ(frame->image.height(), 8);
    ExpectColour(frame->image.at(4, 4), kSquare);  // pixel (24, 16) of the frame
    const ExrMetadata header = FrameJobMetadata("square", job, *frame);
    EXPECT_EQ(header.mode, FrameJobModeName(job));
    EXPECT_EQ(header.scene_name, "square");
    EXPECT_EQ(header.x, 20);
    EXPECT_EQ(header.y, 12);
    EXPECT_EQ(header.frame_width, 48);
    EXPECT_EQ(header.frame_height, 32);
  }
}

}  // namespace
}  // namespace aperture
