// Seed 003's raytrace mode through the service (RenderOptions.mode): a sphere the raster mode
// refuses, regions pixel-identical to the whole frame, option errors naming the field, and a
// deadline that stops a long raytraced frame.
#include <gmock/gmock.h>
#include <grpcpp/grpcpp.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>

#include "frame/camera_proto.h"
#include "integration/service_fixture.h"
#include "scene/scene_builder.h"
#include "support/hostile_inputs.h"
#include "testing/curved_scenes.h"
// After the protobuf headers: OpenImageIO's byte-swap macros break protobuf's port.h.
#include <OpenImageIO/imagebuf.h>

namespace aperture::testing {
namespace {

using ::testing::HasSubstr;

// The RGBA floats of an EXR held in memory.
std::vector<float> Decode(const std::string& exr, int* width, int* height) {
  // A new name each time: OpenImageIO's image cache would hand back an earlier file's pixels.
  static int calls = 0;
  const std::string path =
      std::filesystem::path(::testing::TempDir()) /
      ("aperture_rt_" + std::to_string(getpid()) + "_" + std::to_string(++calls) + ".exr");
  std::ofstream(path, std::ios::binary) << exr;
  OIIO::ImageBuf image(path);
  std::vector<float> pixels;
  if (image.read(0, 0, true, OIIO::TypeDesc::FLOAT)) {
    *width = image.spec().width;
    *height = image.spec().height;
    pixels.resize(static_cast<size_t>(*width) * *height * 4);
    // A region's data window lies at its place in the frame: read the window, wherever it is.
    image.get_pixels(image.roi(), OIIO::TypeDesc::FLOAT, pixels.data());
  }
  std::filesystem::remove(path);
  return pixels;
}

v1::RenderFrameRequest SphereFrame(const std::string& scene_id, const CurvedTestScene& test) {
  v1::RenderFrameRequest request;
  request.set_scene_id(scene_id);
  *request.mutable_camera() = CameraToProto(test.camera);
  request.mutable_options()->set_width(48);
  request.mutable_options()->set_height(40);
  request.mutable_options()->set_mode(v1::RENDER_MODE_RAYTRACE);
  request.mutable_options()->set_pixel_type(v1::PIXEL_TYPE_FLOAT);
  return request;
}

TEST_F(ServiceTest, RaytraceModeDrawsASphereAndItsRegionsMatchTheFrame) {
  StartServer();
  const CurvedTestScene test = MakeCurvedTestScene(CurvedSceneKind::kSphere, 64);
  const std::string id = LoadScene(test.scene);
  v1::RenderFrameRequest request = SphereFrame(id, test);
  v1::RenderFrameResponse whole;
  grpc::Status status = Render(request, 30, &whole);
  ASSERT_TRUE(status.ok()) << status.error_message();
  int w = 0, h = 0;
  const std::vector<float> frame = Decode(whole.exr(), &w, &h);
  ASSERT_EQ(w, 48);
  ASSERT_EQ(h, 40);
  EXPECT_GT(frame[(20 * 48 + 24) * 4 + 0] + frame[(20 * 48 + 25) * 4 + 0], 0.2f);  // the sphere
  EXPECT_EQ(frame[0], 0.0f);                                                       // black sky

  // A band through the sphere: the same pixels as the whole frame's.
  request.mutable_region()->set_x(5);
  request.mutable_region()->set_y(11);
  request.mutable_region()->set_width(30);
  request.mutable_region()->set_height(17);
  v1::RenderFrameResponse band;
  status = Render(request, 30, &band);
  ASSERT_TRUE(status.ok()) << status.error_message();
  const std::vector<float> part = Decode(band.exr(), &w, &h);
  ASSERT_EQ(w, 30);
  ASSERT_EQ(h, 17);
  for (int y = 0; y < 17; ++y)
    for (int x = 0; x < 30; ++x)
      for (int c = 0; c < 4; ++c)
        ASSERT_EQ(part[(y * 30 + x) * 4 + c], frame[((y + 11) * 48 + x + 5) * 4 + c])
            << x << "," << y;

  // The raster mode cannot draw the sphere and says which mode can.
  request.clear_region();
  request.mutable_options()->set_mode(v1::RENDER_MODE_RASTER);
  status = Render(request, 30);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_THAT(status.error_message(), HasSubstr("RENDER_MODE_RAYTRACE"));
}

TEST_F(ServiceTest, RaytraceOptionErrorsNameTheField) {
  StartServer();
  const CurvedTestScene test = MakeCurvedTestScene(CurvedSceneKind::kSphere, 64);
  const std::string id = LoadScene(test.scene);
  v1::RenderFrameRequest request = SphereFrame(id, test);
  request.mutable_options()->set_raytrace_delta(-1);
  grpc::Status status = Render(request, 10);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_THAT(status.error_message(), HasSubstr("options.raytrace_delta is -1"));
  request = SphereFrame(id, test);
  request.mutable_options()->mutable_raytrace_max_depth()->set_value(9);
  status = Render(request, 10);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_THAT(status.error_message(), HasSubstr("options.raytrace_max_depth is 9"));
  request = SphereFrame(id, test);
  request.mutable_options()->set_mode(static_cast<v1::RenderMode>(7));
  status = Render(request, 10);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_THAT(status.error_message(), HasSubstr("options.mode has unknown value 7"));
  // max_depth 0 is a valid depth (set, not defaulted).
  request = SphereFrame(id, test);
  request.mutable_options()->mutable_raytrace_max_depth()->set_value(0);
  request.mutable_options()->set_raytrace_delta(0.3);
  status = Render(request, 30);
  EXPECT_TRUE(status.ok()) << status.error_message();
}

TEST_F(ServiceTest, ADeadlineStopsALongRaytracedFrame) {
  StartServer();
  const std::string id = LoadDemoScene();
  v1::RenderFrameRequest request = FrameRequest(id, 1000, 1000);  // several seconds on two threads
  request.mutable_options()->set_mode(v1::RENDER_MODE_RAYTRACE);
  const auto start = std::chrono::steady_clock::now();
  const grpc::Status status = Render(request, 1.5);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_EQ(status.error_code(), grpc::StatusCode::DEADLINE_EXCEEDED) << status.error_message();
  EXPECT_LT(seconds, 5);
}

// The peak resident memory of process `pid` (VmHWM), in bytes; 0 if it cannot be read.
uint64_t PeakResidentBytes(pid_t pid) {
  std::ifstream status("/proc/" + std::to_string(pid) + "/status");
  std::string line;
  while (std::getline(status, line))
    if (line.rfind("VmHWM:", 0) == 0) return std::stoull(line.substr(6)) << 10;  // kB
  return 0;
}

// A raytraced frame whose summed-area tables cannot fit the store's budget is refused before
// they are built: at once, with the tables' size, the texture and the budget named, and without
// the server's memory growing by the tables (a 1024 x 1024 texture's take about 270 MB, and
// building them before refusing them took seconds and three times that memory).
TEST_F(ServiceTest, RaytraceTablesOverTheStoresBudgetAreRefusedBeforeTheyAreBuilt) {
  StartServer({"--max-store-mb=64"});
  v1::LoadSceneResponse loaded;
  {
    grpc::ClientContext context;
    context.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(30));
    ASSERT_TRUE(stub_->LoadScene(&context, TexturedGroundScene("", 1024), &loaded).ok());
  }
  v1::RenderFrameRequest request = FrameRequest(loaded.scene_id(), 32, 32);
  request.mutable_options()->set_mode(v1::RENDER_MODE_RAYTRACE);
  const uint64_t peak_before = PeakResidentBytes(server_->pid());
  ASSERT_GT(peak_before, 0u);
  const auto start = std::chrono::steady_clock::now();
  const grpc::Status status = Render(request, 60);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_EQ(status.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED) << status.error_message();
  EXPECT_THAT(status.error_message(), HasSubstr("summed-area tables of texture 't' (1024 x 1024"));
  EXPECT_THAT(status.error_message(), HasSubstr("an entry of 2"));  // 2xx MiB
  EXPECT_THAT(status.error_message(), HasSubstr("budget of 64 MiB (--max-store-mb)"));
  EXPECT_LT(seconds, 1.0);
  const uint64_t peak_after = PeakResidentBytes(server_->pid());
  EXPECT_LT(peak_after, peak_before + (64u << 20))
      << "the peak resident memory grew from " << (peak_before >> 20) << " to "
      << (peak_after >> 20) << " MiB";
  EXPECT_LE(Info().budgets().store_bytes(), 64u << 20);
  // Refused again as fast: nothing half-built is kept or retried at length.
  const auto again = std::chrono::steady_clock::now();
  EXPECT_EQ(Render(request, 60).error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED);
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - again).count(), 1.0);
}

}  // namespace
}  // namespace aperture::testing
