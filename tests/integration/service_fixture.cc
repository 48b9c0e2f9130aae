#include "integration/service_fixture.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>
#include <grpcpp/grpcpp.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <utility>

#include "frame/camera_proto.h"
#include "scene/benchmark_scenes.h"
#include "scene/demo_scene.h"
#include "scene/scene_builder.h"

namespace aperture::testing {

std::unique_ptr<ServerProcess> ServiceTest::shared_server_;

v1::LoadSceneResponse LoadBuiltinScene(v1::Render::Stub& stub, const std::string& name) {
  grpc::ClientContext context;
  context.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(30));
  v1::LoadSceneRequest request;
  request.set_builtin_scene(name);
  v1::LoadSceneResponse response;
  const grpc::Status status = stub.LoadScene(&context, request, &response);
  EXPECT_TRUE(status.ok()) << status.error_message();
  return response;
}

void ServiceTest::StartServer(const std::vector<std::string>& args) {
  std::string error;
  std::unique_ptr<ServerProcess>& owner = args.empty() ? shared_server_ : own_server_;
  // The shared server's limits are low enough for the tests of oversized frames and messages.
  if (!owner)
    owner = ServerProcess::Start(
        args.empty() ? std::vector<std::string>{"--max-pixels=1000000", "--max-message-mb=2"}
                     : args,
        &error);
  ASSERT_NE(owner, nullptr) << error;
  server_ = owner.get();
  grpc::ChannelArguments channel_args;
  channel_args.SetMaxReceiveMessageSize(-1);
  stub_ = v1::Render::NewStub(grpc::CreateCustomChannel(
      server_->address(), grpc::InsecureChannelCredentials(), channel_args));
}

std::string ServiceTest::LoadDemoScene() { return LoadScene(MakeDemoScene()); }

v1::RenderFrameRequest ServiceTest::SlowFrame() {
  v1::RenderFrameRequest request;
  // 72,000 slivers (scene/benchmark_scenes.h): every window is mixed, the cost is even over the
  // frame, so a 4096 x 4096 frame takes seconds (8.9 s on one thread of the 2-core machine) but
  // each of its tasks much less.
  request.set_scene_id(LoadScene(MakeSliversScene(72000)));
  request.mutable_camera()->mutable_position();
  request.mutable_options()->set_width(4096);
  request.mutable_options()->set_height(4096);
  request.mutable_options()->set_anti_aliasing(v1::ANTI_ALIASING_TENT2);
  return request;
}

std::string ServiceTest::LoadScene(const v1::Scene& scene) {
  grpc::ClientContext context;
  context.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(30));
  v1::LoadSceneRequest request;
  *request.mutable_scene() = scene;
  v1::LoadSceneResponse response;
  const grpc::Status status = stub_->LoadScene(&context, request, &response);
  EXPECT_TRUE(status.ok()) << status.error_message();
  return response.scene_id();
}

v1::RenderFrameRequest ServiceTest::FrameRequest(const std::string& scene_id, int width,
                                                 int height) const {
  v1::RenderFrameRequest request;
  request.set_scene_id(scene_id);
  *request.mutable_camera() = CameraToProto(DemoCamera());
  request.mutable_options()->set_width(width);
  request.mutable_options()->set_height(height);
  request.mutable_options()->set_filter(v1::TEXTURE_FILTER_TRILINEAR);
  return request;
}

grpc::Status ServiceTest::Render(const v1::RenderFrameRequest& request, double seconds,
                                 v1::RenderFrameResponse* response) {
  grpc::ClientContext context;
  context.set_deadline(std::chrono::system_clock::now() +
                       std::chrono::milliseconds(static_cast<int64_t>(seconds * 1000)));
  v1::RenderFrameResponse ignored;
  return stub_->RenderFrame(&context, request, response ? response : &ignored);
}

v1::GetServerInfoResponse ServiceTest::Info() {
  grpc::ClientContext context;
  context.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(5));
  v1::GetServerInfoResponse response;
  EXPECT_TRUE(stub_->GetServerInfo(&context, {}, &response).ok());
  return response;
}

std::vector<v1::RenderFrameResponse> ServiceTest::ReadAllAnswers(
    grpc::ClientReaderWriter<v1::RenderFrameRequest, v1::RenderFrameResponse>& stream) {
  std::vector<v1::RenderFrameResponse> frames;
  v1::RenderFrameResponse response;
  while (stream.Read(&response)) frames.push_back(response);
  return frames;
}

std::string NoisePng(int width, int height, uint32_t seed) {
  std::vector<uint8_t> texels(static_cast<size_t>(width) * height * 3);
  uint32_t state = seed * 2654435761u + 1;
  for (uint8_t& t : texels) {
    state = state * 1664525u + 1013904223u;
    t = static_cast<uint8_t>(state >> 24);
  }
  const std::string path = ::testing::TempDir() + "aperture_noise_" + std::to_string(getpid()) +
                           "_" + std::to_string(seed) + ".png";
  auto out = OIIO::ImageOutput::create(path);
  EXPECT_TRUE(out && out->open(path, OIIO::ImageSpec(width, height, 3, OIIO::TypeDesc::UINT8)));
  if (!out) return {};
  EXPECT_TRUE(out->write_image(OIIO::TypeDesc::UINT8, texels.data()));
  out->close();
  std::ifstream in(path, std::ios::binary);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  std::remove(path.c_str());
  return bytes.str();
}

std::vector<float> ServiceTest::Pixels(const v1::RenderFrameResponse& response) {
  OIIO::Filesystem::IOMemReader memory(response.exr().data(), response.exr().size());
  OIIO::ImageSpec config;
  OIIO::Filesystem::IOProxy* proxy = &memory;
  config.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
  auto in = OIIO::ImageInput::open("frame.exr", &config);
  if (!in) {
    ADD_FAILURE() << "cannot read the frame's EXR (" << response.exr().size()
                  << " bytes): " << OIIO::geterror();
    return {};
  }
  const OIIO::ImageSpec& spec = in->spec();
  std::vector<float> pixels(static_cast<size_t>(spec.width) * spec.height * spec.nchannels);
  if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, pixels.data())) return {};
  return pixels;
}

}  // namespace aperture::testing
