// Content that exact visibility finds hard, through the service: crowds of coplanar polygons,
// stacks of layers a millimetre apart, ten thousand objects at one place (loaded so, or moved
// there by an update), and a frame over the server's memory budget. Each frame within a generous
// bound of time and of the server's memory (scripts/bench-hostile.sh holds the tight figures).
// Real servers on loopback, real gRPC calls.
#include <gmock/gmock.h>
#include <grpcpp/grpcpp.h>
#include <gtest/gtest.h>

#include <chrono>
#include <string>

#include "frame/camera_proto.h"
#include "integration/service_fixture.h"
#include "scene/camera.h"
#include "support/hostile_inputs.h"
#include "support/hostile_scenes.h"

namespace aperture::testing {
namespace {

using ::testing::HasSubstr;
using Clock = std::chrono::steady_clock;

class HostileContentTest : public ServiceTest {
 protected:
  // A frame of `scene_id` seen from the origin looking along -z, as the hostile scenes are.
  static v1::RenderFrameRequest OriginFrame(const std::string& scene_id, int width, int height) {
    v1::RenderFrameRequest request;
    request.set_scene_id(scene_id);
    Camera camera;
    camera.vertical_fov_deg = 60;
    *request.mutable_camera() = CameraToProto(camera);
    request.mutable_options()->set_width(width);
    request.mutable_options()->set_height(height);
    return request;
  }
  // Renders the frame; expects it within `seconds` and an image in the answer.
  void ExpectRenders(const v1::RenderFrameRequest& request, double seconds, const char* what) {
    v1::RenderFrameResponse response;
    const auto start = Clock::now();
    const grpc::Status status = Render(request, 120, &response);
    const double elapsed = std::chrono::duration<double>(Clock::now() - start).count();
    ASSERT_TRUE(status.ok()) << what << ": " << status.error_message();
    EXPECT_LT(elapsed, seconds) << what;
    EXPECT_EQ(Pixels(response).size(), 4u * request.options().width() * request.options().height())
        << what;
    std::printf("%s, %dx%d: %.3f s\n", what, request.options().width(), request.options().height(),
                elapsed);
  }
};

// Each frame in well under a second where 27 layers of coplanar copies once grew the process by a
// gigabyte a second, 200 triangles a millimetre apart took seconds and ten thousand copies of a
// quad ran past any deadline.
TEST_F(HostileContentTest, CoplanarCrowdsStacksAndCopiesRenderWithinBounds) {
  StartServer({"--threads=2"});
  const double start_mb = server_->PeakResidentMb();
  const std::pair<const char*, v1::Scene> scenes[] = {
      {"8,000 coplanar triangles 27 deep", CoplanarCrowdScene(false)},
      {"296 coplanar triangles placed 27 times each", CoplanarLayersScene()},
      {"10 triangles in 20 layers 1 mm apart", StackedLayersScene(false)},
      {"10,000 copies of a quad at one place", CopiesScene(10000)}};
  for (const auto& [what, scene] : scenes) {
    const std::string id = LoadScene(scene);
    ExpectRenders(OriginFrame(id, 64, 48), 1, what);
    ExpectRenders(OriginFrame(id, 1920, 1080), 5, what);
  }
  const double grown_mb = server_->PeakResidentMb() - start_mb;
  std::printf("server peak resident set grew by %.0f MiB\n", grown_mb);
  EXPECT_LT(grown_mb, 800);
}

// A valid update that moves ten thousand named objects into one spot of one plane, then frames
// of the stream.
TEST_F(HostileContentTest, AnUpdateMovingTenThousandObjectsToOneSpotRendersWithinBounds) {
  StartServer({"--threads=2"});
  const double start_mb = server_->PeakResidentMb();
  const std::string id = LoadScene(ManyObjectsScene(10000));
  v1::RenderFrameRequest request = OriginFrame(id, 64, 48);
  Camera camera;  // above the ground, looking down at the spot
  camera.position = {0, 3, 0};
  camera.pitch_deg = -60;
  camera.vertical_fov_deg = 60;
  *request.mutable_camera() = CameraToProto(camera);
  for (int i = 0; i < 10000; ++i) {
    v1::ObjectUpdate& o = *request.mutable_update()->add_objects();
    o.set_name("object-" + std::to_string(i));
    o.mutable_transform()->mutable_translation()->set_z(-2);
  }
  ExpectRenders(request, 1, "10,000 objects moved to one spot");
  request.clear_update();
  request.mutable_options()->set_width(1920);
  request.mutable_options()->set_height(1080);
  ExpectRenders(request, 5, "10,000 objects moved to one spot");
  const double grown_mb = server_->PeakResidentMb() - start_mb;
  std::printf("server peak resident set grew by %.0f MiB\n", grown_mb);
  EXPECT_LT(grown_mb, 800);
}

// Over its budget a frame stops with RESOURCE_EXHAUSTED naming the budget, the server logs it as
// every frame, and the next frame renders.
TEST_F(HostileContentTest, AFrameOverTheMemoryBudgetIsRefusedAndTheServerGoesOn) {
  StartServer({"--max-frame-mb=16"});
  const std::string id = LoadScene(CoplanarCrowdScene(false));
  v1::RenderFrameResponse response;
  const grpc::Status status = Render(OriginFrame(id, 1920, 1080), 30, &response);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED) << status.error_message();
  EXPECT_THAT(status.error_message(), HasSubstr("budget of 16 MiB"));
  EXPECT_THAT(status.error_message(), HasSubstr("--max-frame-mb"));
  EXPECT_THAT(server_->Log(), HasSubstr("status=RESOURCE_EXHAUSTED"));
  ExpectRenders(OriginFrame(id, 320, 240), 20, "the next frame, within the budget");
}

}  // namespace
}  // namespace aperture::testing
