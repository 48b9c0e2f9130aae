// What the service tests share: a server started per test, a stub to it, the demo scene loaded
// on it, and frame requests that render quickly (small, trilinear filter).
#pragma once

#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "aperture/v1/render_service.grpc.pb.h"
#include "integration/server_process.h"

namespace aperture::testing {

// LoadScene of a built-in scene ("demo", ...) on `stub`; fails the test if it is refused.
v1::LoadSceneResponse LoadBuiltinScene(v1::Render::Stub& stub, const std::string& name);

// A PNG of `width` x `height` RGB noise (about 3 bytes a texel: noise does not compress), written
// by OpenImageIO: a real texture upload.
std::string NoisePng(int width, int height, uint32_t seed);

class ServiceTest : public ::testing::Test {
 protected:
  // Starts aperture-server with these extra flags; fails the test if it does not come up.
  // Without flags, the tests of a suite share one server (started once, killed at the end).
  void StartServer(const std::vector<std::string>& args = {});
  static void TearDownTestSuite() { shared_server_.reset(); }
  // Loads a scene and returns its id.
  std::string LoadScene(const v1::Scene& scene);
  // The built-in demo scene (inline textures).
  std::string LoadDemoScene();
  // A frame that takes many seconds even on two fast threads (24000 short thin triangles, every
  // window mixed, tent filter, 2048 x 2048) in tasks of a fraction of a second: longer than any
  // deadline or grace period of the tests, yet quick to stop.
  v1::RenderFrameRequest SlowFrame();
  // The demo camera, trilinear filter, `width` x `height`.
  v1::RenderFrameRequest FrameRequest(const std::string& scene_id, int width, int height) const;
  // A RenderFrame call with a deadline `seconds` from now.
  grpc::Status Render(const v1::RenderFrameRequest& request, double seconds,
                      v1::RenderFrameResponse* response = nullptr);
  v1::GetServerInfoResponse Info();
  // Every answer of a stream whose writes are done, in the order they came.
  static std::vector<v1::RenderFrameResponse> ReadAllAnswers(
      grpc::ClientReaderWriter<v1::RenderFrameRequest, v1::RenderFrameResponse>& stream);
  // The RGBA pixels of an answer's EXR, read back by OpenImageIO (empty if it cannot be read).
  static std::vector<float> Pixels(const v1::RenderFrameResponse& response);

  static std::unique_ptr<ServerProcess> shared_server_;
  std::unique_ptr<ServerProcess> own_server_;
  ServerProcess* server_ = nullptr;
  std::unique_ptr<v1::Render::Stub> stub_;
};

}  // namespace aperture::testing
