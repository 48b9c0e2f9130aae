// A hostile soak of one aperture-server on loopback: N clients for M
// minutes, each looping over a random mix of
//   valid frames of the demo (their pixels compared with a local render of the same request),
//   invalid requests (unknown scene, zero size, NaN camera, a pentagram),
//   bombs (a PNG declaring 16384^2 texels; one declaring 8192^2, uploaded, then loaded),
//   stalled uploads (8 MiB announced, 1 KiB sent, then silence until the server cancels),
//   scene churn (a fresh noise texture uploaded and loaded, aniso half the time, one frame of it).
// Each answer's status is checked against the codes that operation may give; anything else is
// "unexpected" and printed. Run by scripts/bench-hostile.sh, which watches the server's RSS and
// the store's bytes. Usage: hostile_soak --server HOST:PORT [--clients 32] [--seconds 300]
// Protobuf's headers before OpenImageIO's, whose farmhash.h #undefs the bswap_32 and bswap_64
// that protobuf's port.h uses.
#include "aperture/v1/render_service.grpc.pb.h"
// clang-format off
#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>
// clang-format on
#include <grpcpp/grpcpp.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <mutex>
#include <random>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "content_hash.h"
#include "frame/camera_proto.h"
#include "frame_request.h"
#include "io/exr_writer.h"
#include "render/frame_renderer.h"
#include "scene/builtin_scenes.h"
#include "scene/camera.h"
#include "scene/demo_scene.h"
#include "scene/scene_builder.h"
#include "support/hostile_inputs.h"

namespace aperture {
namespace {

using Clock = std::chrono::steady_clock;
using grpc::StatusCode;

std::vector<float> DecodeExr(const std::string& bytes) {
  OIIO::Filesystem::IOMemReader memory(bytes.data(), bytes.size());
  OIIO::ImageSpec config;
  OIIO::Filesystem::IOProxy* proxy = &memory;
  config.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
  auto in = OIIO::ImageInput::open("frame.exr", &config);
  if (!in) return {};
  const OIIO::ImageSpec& spec = in->spec();
  std::vector<float> pixels(static_cast<size_t>(spec.width) * spec.height * spec.nchannels);
  if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, pixels.data())) return {};
  return pixels;
}

std::string EncodePng(int width, int height, uint32_t seed) {
  std::vector<uint8_t> texels(static_cast<size_t>(width) * height * 3);
  std::mt19937 rng(seed);
  for (uint8_t& t : texels) t = static_cast<uint8_t>(rng());
  std::vector<unsigned char> out;
  OIIO::Filesystem::IOVecOutput vec(out);
  OIIO::ImageSpec spec(width, height, 3, OIIO::TypeDesc::UINT8);
  OIIO::Filesystem::IOProxy* proxy = &vec;
  spec.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
  auto png = OIIO::ImageOutput::create("noise.png");
  if (!png || !png->open("noise.png", spec)) return {};
  png->write_image(OIIO::TypeDesc::UINT8, texels.data());
  png->close();
  return std::string(out.begin(), out.end());
}

class Soak {
 public:
  Soak(std::string server, int clients, double seconds)
      : server_(std::move(server)), clients_(clients), seconds_(seconds) {}

  int Run() {
    grpc::ChannelArguments args;
    args.SetMaxReceiveMessageSize(-1);
    channel_ = grpc::CreateCustomChannel(server_, grpc::InsecureChannelCredentials(), args);
    auto stub = v1::Render::NewStub(channel_);
    {
      grpc::ClientContext context;
      v1::LoadSceneRequest request;
      request.set_builtin_scene("demo");
      v1::LoadSceneResponse response;
      const grpc::Status status = stub->LoadScene(&context, request, &response);
      if (!status.ok()) {
        std::fprintf(stderr, "hostile_soak: cannot load the demo: %s\n",
                     status.error_message().c_str());
        return 2;
      }
      demo_id_ = response.scene_id();
    }
    if (!PrepareReferences()) return 2;
    std::printf("hostile_soak: %d clients for %.0f s against %s\n", clients_, seconds_,
                server_.c_str());
    std::fflush(stdout);
    const Clock::time_point end = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                                     std::chrono::duration<double>(seconds_));
    std::vector<std::thread> threads;
    for (int c = 0; c < clients_; ++c) threads.emplace_back([this, c, end] { Client(c, end); });
    for (std::thread& t : threads) t.join();
    return Report();
  }

 private:
  static constexpr int kCameras = 8;

  v1::RenderFrameRequest DemoFrame(int camera) const {
    v1::RenderFrameRequest request;
    request.set_scene_id(demo_id_);
    Camera c = DemoCamera();
    c.yaw_deg += 7.5 * camera;
    *request.mutable_camera() = CameraToProto(c);
    request.mutable_options()->set_width(96);
    request.mutable_options()->set_height(54);
    request.mutable_options()->set_filter(v1::TEXTURE_FILTER_TRILINEAR);
    return request;
  }

  // The pixels each demo frame must have: the same requests rendered here by the engine.
  bool PrepareReferences() {
    auto builtin = FindBuiltinScene("demo");
    if (!builtin.ok()) return false;
    auto scene = BuildScene(builtin->scene);
    if (!scene.ok()) return false;
    for (int c = 0; c < kCameras; ++c) {
      auto job = ParseFrameRequest(DemoFrame(c), 1u << 24);
      if (!job.ok()) return false;
      job->settings.threads = 1;
      auto frame = RenderFrame(*scene, job->camera, job->settings);
      if (!frame.ok()) return false;
      auto exr = EncodeExr(frame->image, job->exr);
      if (!exr.ok()) return false;
      references_.push_back(DecodeExr(*exr));
      if (references_.back().empty()) return false;
    }
    return true;
  }

  void Count(const std::string& op, const grpc::Status& status,
             std::initializer_list<StatusCode> expected) {
    std::lock_guard lock(mutex_);
    const std::string key =
        op + " " + absl::StatusCodeToString(static_cast<absl::StatusCode>(status.error_code()));
    ++counts_[key];
    for (StatusCode code : expected)
      if (status.error_code() == code) return;
    ++unexpected_;
    if (unexpected_ <= 20)
      std::printf("unexpected: %s: %s\n", key.c_str(), status.error_message().c_str());
  }

  grpc::Status Upload(v1::Render::Stub& stub, const std::string& bytes) {
    grpc::ClientContext context;
    context.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(60));
    v1::UploadTextureResponse response;
    auto writer = stub.UploadTexture(&context, &response);
    for (size_t offset = 0; offset < bytes.size(); offset += 1 << 20) {
      v1::UploadTextureRequest message;
      if (offset == 0) {
        message.set_sha256(Sha256Hex(bytes));
        message.set_total_size(bytes.size());
      }
      message.set_chunk(bytes.substr(offset, 1 << 20));
      if (!writer->Write(message)) break;
    }
    writer->WritesDone();
    return writer->Finish();
  }

  grpc::Status Load(v1::Render::Stub& stub, const v1::LoadSceneRequest& request, std::string* id) {
    grpc::ClientContext context;
    context.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(60));
    v1::LoadSceneResponse response;
    const grpc::Status status = stub.LoadScene(&context, request, &response);
    if (id != nullptr) *id = response.scene_id();
    return status;
  }

  grpc::Status Render(v1::Render::Stub& stub, const v1::RenderFrameRequest& request,
                      v1::RenderFrameResponse* response) {
    grpc::ClientContext context;
    context.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(60));
    return stub.RenderFrame(&context, request, response);
  }

  void Client(int index, Clock::time_point end) {
    auto stub = v1::Render::NewStub(channel_);
    std::mt19937 rng(1000 + index);
    const std::string bomb16k = testing::PngDeclaring(16384, 16384);
    const std::string bomb8k = testing::PngDeclaring(8192, 8192);
    uint32_t churn = static_cast<uint32_t>(index) << 20;
    while (Clock::now() < end) {
      const int what = static_cast<int>(rng() % 100);
      if (what < 50) {  // a valid frame, compared with the local render
        const int camera = static_cast<int>(rng() % kCameras);
        v1::RenderFrameResponse response;
        const grpc::Status status = Render(*stub, DemoFrame(camera), &response);
        Count("frame", status, {StatusCode::OK, StatusCode::RESOURCE_EXHAUSTED});
        if (status.ok()) {
          const bool same = DecodeExr(response.exr()) == references_[camera];
          std::lock_guard lock(mutex_);
          ++(same ? frames_identical_ : frames_different_);
        }
      } else if (what < 65) {  // invalid requests
        v1::RenderFrameResponse response;
        v1::RenderFrameRequest unknown = DemoFrame(0);
        unknown.set_scene_id(std::string(64, 'f'));
        Count("invalid", Render(*stub, unknown, &response), {StatusCode::NOT_FOUND});
        v1::RenderFrameRequest empty = DemoFrame(0);
        empty.mutable_options()->set_width(0);
        Count("invalid", Render(*stub, empty, &response), {StatusCode::INVALID_ARGUMENT});
        v1::RenderFrameRequest nan = DemoFrame(0);
        nan.mutable_camera()->mutable_position()->set_x(std::nan(""));
        Count("invalid", Render(*stub, nan, &response), {StatusCode::INVALID_ARGUMENT});
        v1::LoadSceneRequest star;
        v1::Polygon& poly = *star.mutable_scene()->add_meshes()->add_polygons();
        star.mutable_scene()->mutable_meshes(0)->set_id("star");
        for (int k = 0; k < 5; ++k) {
          v1::Vec3& v = *poly.add_vertices();
          v.set_x(std::cos(4 * M_PI * k / 5));
          v.set_z(std::sin(4 * M_PI * k / 5));
        }
        Count("invalid", Load(*stub, star, nullptr), {StatusCode::INVALID_ARGUMENT});
      } else if (what < 75) {  // bombs
        Count("bomb-16k", Upload(*stub, bomb16k), {StatusCode::INVALID_ARGUMENT});
        const grpc::Status kept = Upload(*stub, bomb8k);
        Count("bomb-8k-upload", kept, {StatusCode::OK, StatusCode::RESOURCE_EXHAUSTED});
        if (kept.ok())
          Count("bomb-8k-load",
                Load(*stub, testing::TexturedGroundScene(Sha256Hex(bomb8k)), nullptr),
                {StatusCode::RESOURCE_EXHAUSTED, StatusCode::NOT_FOUND});
      } else if (what < 80) {  // a stalled upload: the server must cancel it
        grpc::ClientContext context;
        context.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(60));
        v1::UploadTextureResponse response;
        auto writer = stub->UploadTexture(&context, &response);
        v1::UploadTextureRequest message;
        message.set_sha256(Sha256Hex(std::to_string(rng())));
        message.set_total_size(8 << 20);
        message.set_chunk(std::string(1024, 's'));
        writer->Write(message);
        Count("stalled-upload", writer->Finish(),
              {StatusCode::CANCELLED, StatusCode::RESOURCE_EXHAUSTED});
      } else {  // scene churn
        const std::string png = EncodePng(256, 256, ++churn);
        const grpc::Status uploaded = Upload(*stub, png);
        Count("churn-upload", uploaded, {StatusCode::OK, StatusCode::RESOURCE_EXHAUSTED});
        if (!uploaded.ok()) continue;
        std::string id;
        // NOT_FOUND: the store evicted the upload before the load (other clients' churn).
        const grpc::Status loaded =
            Load(*stub, testing::TexturedGroundScene(Sha256Hex(png), 0, rng() % 2 == 1), &id);
        Count("churn-load", loaded,
              {StatusCode::OK, StatusCode::RESOURCE_EXHAUSTED, StatusCode::NOT_FOUND});
        if (!loaded.ok()) continue;
        v1::RenderFrameRequest frame = DemoFrame(0);
        frame.set_scene_id(id);
        v1::RenderFrameResponse response;
        // NOT_FOUND: the scene was evicted (other clients' churn) before its frame.
        Count("churn-frame", Render(*stub, frame, &response),
              {StatusCode::OK, StatusCode::RESOURCE_EXHAUSTED, StatusCode::NOT_FOUND});
      }
    }
  }

  int Report() {
    std::printf("%-34s %8s\n", "operation and status", "count");
    for (const auto& [key, count] : counts_)
      std::printf("%-34s %8llu\n", key.c_str(), static_cast<unsigned long long>(count));
    std::printf("valid frames: %llu pixel-identical to the local render, %llu different\n",
                static_cast<unsigned long long>(frames_identical_),
                static_cast<unsigned long long>(frames_different_));
    std::printf("unexpected status codes: %llu\n", static_cast<unsigned long long>(unexpected_));
    return unexpected_ == 0 && frames_different_ == 0 && frames_identical_ > 0 ? 0 : 1;
  }

  const std::string server_;
  const int clients_;
  const double seconds_;
  std::shared_ptr<grpc::Channel> channel_;
  std::string demo_id_;
  std::vector<std::vector<float>> references_;
  std::mutex mutex_;
  std::map<std::string, uint64_t> counts_;
  uint64_t unexpected_ = 0, frames_identical_ = 0, frames_different_ = 0;
};

}  // namespace
}  // namespace aperture

int main(int argc, char** argv) {
  std::string server = "127.0.0.1:50051";
  int clients = 32;
  double seconds = 300;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string flag = argv[i];
    if (flag == "--server")
      server = argv[i + 1];
    else if (flag == "--clients")
      clients = std::atoi(argv[i + 1]);
    else if (flag == "--seconds")
      seconds = std::atof(argv[i + 1]);
  }
  if (server.rfind("127.", 0) != 0 && server.rfind("localhost", 0) != 0) {
    std::fprintf(stderr, "hostile_soak: loopback servers only (127.0.0.0/8, localhost)\n");
    return 2;
  }
  return aperture::Soak(server, clients, seconds).Run();
}
