// The frame request as the engine's job: the rendering process's own choices (FrameJobOptions)
// reach the job's settings, EXR options and trace options; left at their defaults they leave the
// job as the request alone makes it; a bad one is refused naming it.
#include "frame/frame_job.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace aperture {
namespace {

using ::testing::HasSubstr;

v1::RenderFrameRequest Request() {
  v1::RenderFrameRequest request;
  request.mutable_camera()->mutable_position()->set_y(1);
  request.mutable_options()->set_width(64);
  request.mutable_options()->set_height(48);
  request.mutable_options()->set_mode(v1::RENDER_MODE_RAYTRACE);
  return request;
}

TEST(FrameJob, DefaultOptionsAreTheEngineDefaults) {
  auto job = FrameJobFromRequest(Request());
  ASSERT_TRUE(job.ok()) << job.status();
  const RenderSettings defaults;
  EXPECT_EQ(job->settings.threads, 0);
  EXPECT_EQ(job->settings.max_frame_bytes, 0u);
  EXPECT_EQ(job->settings.warnock.leaf_size, defaults.warnock.leaf_size);
  EXPECT_EQ(job->settings.warnock.crowded_leaf_size, defaults.warnock.crowded_leaf_size);
  EXPECT_EQ(job->settings.scheduling.mode, Scheduling::kCost);
  EXPECT_EQ(job->settings.scheduling.uniform_tile, defaults.scheduling.uniform_tile);
  EXPECT_EQ(job->exr.zip_level, 4);
  EXPECT_EQ(job->exr.threads, 0);
  EXPECT_EQ(job->mode.trace.fragments.exact_steps, 256);
  EXPECT_TRUE(job->mode.raytrace);
  EXPECT_EQ(job->settings.width, 64);
}

TEST(FrameJob, LocalOptionsReachTheJob) {
  FrameJobOptions local;
  local.threads = 3;
  local.max_frame_bytes = 5 << 20;
  local.warnock.leaf_size = 8;
  local.warnock.crowded_leaf_size = 32;
  local.scheduling = Scheduling::kUniform;
  local.uniform_tile = 24;
  local.zip_level = 9;
  local.exact_steps = 0;
  auto job = FrameJobFromRequest(Request(), local);
  ASSERT_TRUE(job.ok()) << job.status();
  EXPECT_EQ(job->settings.threads, 3);
  EXPECT_EQ(job->exr.threads, 3);  // encoding on the rendering's threads
  EXPECT_EQ(job->settings.max_frame_bytes, size_t{5} << 20);
  EXPECT_EQ(job->settings.warnock.leaf_size, 8);
  EXPECT_EQ(job->settings.warnock.crowded_leaf_size, 32);
  EXPECT_EQ(job->settings.scheduling.mode, Scheduling::kUniform);
  EXPECT_EQ(job->settings.scheduling.uniform_tile, 24);
  EXPECT_EQ(job->exr.zip_level, 9);
  EXPECT_EQ(job->mode.trace.fragments.exact_steps, 0);
  // The request's own values stay the request's.
  EXPECT_EQ(job->settings.width, 64);
  EXPECT_EQ(job->settings.height, 48);
  EXPECT_TRUE(job->mode.raytrace);
}

TEST(FrameJob, BadLocalOptionsAreRefusedNamingThem) {
  const auto refused = [](const FrameJobOptions& local) {
    return FrameJobFromRequest(Request(), local).status();
  };
  FrameJobOptions zip;
  zip.zip_level = 0;
  EXPECT_THAT(refused(zip).message(), HasSubstr("zip_level 0 is outside 1..9"));
  zip.zip_level = 10;
  EXPECT_EQ(refused(zip).code(), absl::StatusCode::kInvalidArgument);
  FrameJobOptions steps;
  steps.exact_steps = -1;
  EXPECT_THAT(refused(steps).message(), HasSubstr("exact_steps"));
  FrameJobOptions leaf;
  leaf.warnock.leaf_size = 0;
  EXPECT_THAT(refused(leaf).message(), HasSubstr("leaf size"));
  FrameJobOptions tile;
  tile.uniform_tile = 4;
  EXPECT_THAT(refused(tile).message(), HasSubstr("uniform tiles"));
  FrameJobOptions threads;
  threads.threads = -2;
  EXPECT_THAT(refused(threads).message(), HasSubstr("threads"));
}

}  // namespace
}  // namespace aperture
