// The frame flags `aperture` and `aperture-render` share (common/frame_flags.h), through the
// request to the engine's job (frame/frame_job.h): every name a flag takes reaches the engine value
// of that name, so the proto, the flags and the engine cannot drift apart.
#include "frame_flags.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "absl/flags/flag.h"
#include "absl/flags/reflection.h"
#include "frame/frame_job.h"

namespace aperture {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;

absl::StatusOr<FrameJob> JobFromFlags() {
  auto request = FrameRequestFromFlags(std::nullopt, {});
  if (!request.ok()) return request.status();
  return FrameJobFromRequest(*request);
}

TEST(FrameFlags, EnumNamesComeFromTheProto) {
  EXPECT_THAT(EnumFlagNames(*v1::AntiAliasing_descriptor()), ElementsAre("box1", "box2", "tent2"));
  EXPECT_THAT(EnumFlagNames(*v1::ExrCompression_descriptor()),
              ElementsAre("none", "rle", "zips", "zip", "piz", "dwaa", "b44", "b44a", "dwab"));
  EXPECT_THAT(EnumFlagNames(*v1::RenderMode_descriptor()), ElementsAre("raster", "raytrace"));
  EXPECT_EQ(EnumFlagNames(*v1::TextureFilter_descriptor()).size(), 6u);
}

TEST(FrameFlags, EveryNameReachesTheEngineValueOfThatName) {
  absl::FlagSaver saver;
  for (const std::string& name : EnumFlagNames(*v1::AntiAliasing_descriptor())) {
    absl::SetFlag(&FLAGS_aa, name);
    auto job = JobFromFlags();
    ASSERT_TRUE(job.ok()) << job.status();
    EXPECT_EQ(AntiAliasingName(job->settings.aa), name);
  }
  for (const std::string& name : EnumFlagNames(*v1::TextureFilter_descriptor())) {
    absl::SetFlag(&FLAGS_filter, name);
    auto job = JobFromFlags();
    ASSERT_TRUE(job.ok()) << job.status();
    EXPECT_TRUE(job->settings.shading.override_filter);
    EXPECT_EQ(FilterModeName(job->settings.shading.filter), name);
  }
  for (const std::string& name : EnumFlagNames(*v1::ExrCompression_descriptor())) {
    absl::SetFlag(&FLAGS_compression, name);
    auto job = JobFromFlags();
    ASSERT_TRUE(job.ok()) << job.status();
    EXPECT_EQ(ExrCompressionName(job->exr.compression), name);
  }
  for (const std::string& name : EnumFlagNames(*v1::RenderMode_descriptor())) {
    absl::SetFlag(&FLAGS_mode, name);
    auto job = JobFromFlags();
    ASSERT_TRUE(job.ok()) << job.status();
    EXPECT_EQ(job->mode.raytrace, name == "raytrace");
  }
}

// Without --compression the request leaves the codec to its default (zip), so that a command
// may choose its own (aperture sim's for a remote server); a name given is always sent.
TEST(FrameFlags, CompressionUnsetIsTheDefaultAndAGivenNameIsSent) {
  absl::FlagSaver saver;
  auto request = FrameRequestFromFlags(std::nullopt, {});
  ASSERT_TRUE(request.ok());
  EXPECT_EQ(request->options().compression(), v1::EXR_COMPRESSION_DEFAULT);
  auto job = FrameJobFromRequest(*request);
  ASSERT_TRUE(job.ok());
  EXPECT_EQ(job->exr.compression, ExrCompression::kZip);
  absl::SetFlag(&FLAGS_compression, "zip");
  request = FrameRequestFromFlags(std::nullopt, {});
  ASSERT_TRUE(request.ok());
  EXPECT_EQ(request->options().compression(), v1::EXR_COMPRESSION_ZIP);
}

TEST(FrameFlags, HelpAndErrorsListEveryName) {
  absl::FlagSaver saver;
  for (const auto& [flag, descriptor] : {std::pair{"aa", v1::AntiAliasing_descriptor()},
                                         {"filter", v1::TextureFilter_descriptor()},
                                         {"mode", v1::RenderMode_descriptor()},
                                         {"compression", v1::ExrCompression_descriptor()}}) {
    const std::string help = absl::FindCommandLineFlag(flag)->Help();
    auto error = EnumFromFlag(*descriptor, flag, "nonsense");
    ASSERT_FALSE(error.ok());
    EXPECT_THAT(error.status().message(), HasSubstr(absl::StrCat("--", flag, " 'nonsense'")));
    for (const std::string& name : EnumFlagNames(*descriptor)) {
      EXPECT_THAT(help, HasSubstr(name)) << flag;
      EXPECT_THAT(error.status().message(), HasSubstr(name));
    }
  }
  absl::SetFlag(&FLAGS_mode, "both");  // aperture-render's only
  EXPECT_FALSE(FrameRequestFromFlags(std::nullopt, {}).ok());
  bool both = false;
  auto request = FrameRequestFromFlags(std::nullopt, {}, &both);
  ASSERT_TRUE(request.ok());
  EXPECT_TRUE(both);
  EXPECT_EQ(request->options().mode(), v1::RENDER_MODE_RAYTRACE);
  EXPECT_TRUE(request->options().has_raytrace_max_depth());
}

TEST(FrameFlags, CameraFromNumbersFromAModelOrTheScenes) {
  absl::FlagSaver saver;
  v1::Camera own;
  own.mutable_position()->set_x(5);
  own.set_near(0.5);
  own.set_vertical_fov_deg(30);
  // The scene's own camera, its near and field of view kept; --fov overrides the latter, and a
  // camera without one gets 60 degrees.
  auto request = FrameRequestFromFlags(own, {});
  ASSERT_TRUE(request.ok());
  EXPECT_EQ(request->camera().position().x(), 5);
  EXPECT_EQ(request->camera().near(), 0.5);
  EXPECT_EQ(request->camera().vertical_fov_deg(), 30);
  absl::SetFlag(&FLAGS_fov, 45);
  request = FrameRequestFromFlags(own, {});
  ASSERT_TRUE(request.ok());
  EXPECT_EQ(request->camera().vertical_fov_deg(), 45);
  absl::SetFlag(&FLAGS_fov, 0);
  own.clear_vertical_fov_deg();
  request = FrameRequestFromFlags(own, {});
  ASSERT_TRUE(request.ok());
  EXPECT_EQ(request->camera().vertical_fov_deg(), 60);
  own.set_vertical_fov_deg(30);

  absl::SetFlag(&FLAGS_camera, "1,2,3,10,-5,0");
  request = FrameRequestFromFlags(own, {});
  ASSERT_TRUE(request.ok());
  EXPECT_EQ(request->camera().position().z(), 3);
  EXPECT_EQ(request->camera().pitch_deg(), -5);
  EXPECT_EQ(request->camera().near(), 0.5);

  for (const char* bad : {"1,2,3", "1,2,3,4,5,x", "1,2,3,4,5,6,7", ""}) {
    v1::Camera camera;
    EXPECT_FALSE(ParseCameraInto(bad, &camera).ok()) << bad;
  }
  // Not finite: the engine refuses it and names the field, for the server and aperture-render.
  absl::SetFlag(&FLAGS_camera, "nan,0,0,0,0,0");
  auto job = JobFromFlags();
  ASSERT_FALSE(job.ok());
  EXPECT_THAT(job.status().message(), HasSubstr("camera position is not finite"));

  GltfCamera a{.name = "a", .camera = {}}, b{.name = "b", .camera = {}};
  a.camera.set_vertical_fov_deg(20);
  b.camera.set_vertical_fov_deg(40);
  absl::SetFlag(&FLAGS_camera, "");
  request = FrameRequestFromFlags(std::nullopt, {a, b});  // the first by default, its own fov
  ASSERT_TRUE(request.ok());
  EXPECT_EQ(request->camera().vertical_fov_deg(), 20);
  absl::SetFlag(&FLAGS_camera, "b");
  request = FrameRequestFromFlags(std::nullopt, {a, b});
  ASSERT_TRUE(request.ok());
  EXPECT_EQ(request->camera().vertical_fov_deg(), 40);
  absl::SetFlag(&FLAGS_camera, "c");
  request = FrameRequestFromFlags(std::nullopt, {a, b});
  ASSERT_FALSE(request.ok());
  EXPECT_THAT(request.status().message(), HasSubstr("(a, b)"));
}

TEST(FrameFlags, SizeAndRegion) {
  absl::FlagSaver saver;
  uint32_t w = 0, h = 0;
  EXPECT_TRUE(ParseSize("640x480", &w, &h).ok());
  EXPECT_EQ(w, 640u);
  EXPECT_EQ(h, 480u);
  for (const char* bad : {"640", "x480", "640x", "-1x5", "640x480x2", "1234567890x1", "+5x5"})
    EXPECT_FALSE(ParseSize(bad, &w, &h).ok()) << bad;

  absl::SetFlag(&FLAGS_size, "64x32");
  absl::SetFlag(&FLAGS_region, "8,4,16x8");
  auto job = JobFromFlags();
  ASSERT_TRUE(job.ok()) << job.status();
  EXPECT_EQ(job->settings.region.x0, 8);
  EXPECT_EQ(job->settings.region.y1, 12);
  absl::SetFlag(&FLAGS_region, "60,0,16x8");  // beyond the frame: the engine names the region
  job = JobFromFlags();
  ASSERT_FALSE(job.ok());
  EXPECT_THAT(job.status().message(), HasSubstr("region"));
}

}  // namespace
}  // namespace aperture
