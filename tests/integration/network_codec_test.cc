// Frames for a network through a real server: B44A frames (RenderFrame and RenderStream) decode
// with OpenImageIO and stay within their documented PSNR of the half frame (docs/SERVICE.md,
// "Compression for a remote server"); B44 and DWAB round-trip; float pixels with B44 are
// INVALID_ARGUMENT naming the option; `aperture sim` keeps zip on loopback and sends what
// --compression names.
// Protobuf's headers before OpenImageIO's, whose farmhash.h #undefs the bswap_32 and bswap_64
// that protobuf's port.h needs.
// clang-format off
#include <grpcpp/grpcpp.h>
#include "aperture/v1/render_service.grpc.pb.h"
// clang-format on
#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "integration/server_process.h"
#include "integration/service_fixture.h"
#include "support/srgb_psnr.h"

namespace aperture::testing {
namespace {

using ::testing::HasSubstr;

// docs/SERVICE.md: B44A frames of the airport at 1280x720 are within 70 dB (sRGB-encoded RGB)
// of the half frame (73.2 dB measured); any built-in scene's within 55 dB (the night, 59 dB).
constexpr double kB44aAirportPsnrDb = 70;
constexpr double kLossyCodecPsnrDb = 55;

class NetworkCodecTest : public ServiceTest {
 protected:
  void SetUp() override {
    ASSERT_NO_FATAL_FAILURE(StartServer());
    const v1::LoadSceneResponse airport = LoadBuiltinScene(*stub_, "airport");
    ASSERT_FALSE(airport.scene_id().empty());
    request_.set_scene_id(airport.scene_id());
    *request_.mutable_camera() = airport.default_camera();
    request_.mutable_options()->set_width(1280);
    request_.mutable_options()->set_height(720);
  }

  // The frame in `compression`, half pixels; fails the test if it is not rendered.
  v1::RenderFrameResponse RenderIn(v1::ExrCompression compression) {
    v1::RenderFrameRequest request = request_;
    request.mutable_options()->set_compression(compression);
    v1::RenderFrameResponse response;
    const grpc::Status status = Render(request, 60, &response);
    EXPECT_TRUE(status.ok()) << status.error_message();
    return response;
  }

  // The compression the EXR's header names.
  static std::string CompressionOf(const std::string& exr) {
    OIIO::Filesystem::IOMemReader memory(exr.data(), exr.size());
    OIIO::ImageSpec config;
    OIIO::Filesystem::IOProxy* proxy = &memory;
    config.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
    auto in = OIIO::ImageInput::open("frame.exr", &config);
    return in ? in->spec().get_string_attribute("compression") : "(unreadable)";
  }

  v1::RenderFrameRequest request_;
};

TEST_F(NetworkCodecTest, B44aFramesDecodeWithOpenImageIOWithinTheirPsnr) {
  const v1::RenderFrameResponse half = RenderIn(v1::EXR_COMPRESSION_NONE);
  const std::vector<float> reference = Pixels(half);
  ASSERT_EQ(reference.size(), 1280u * 720 * 4);

  const v1::RenderFrameResponse b44a = RenderIn(v1::EXR_COMPRESSION_B44A);
  EXPECT_EQ(CompressionOf(b44a.exr()), "b44a");
  EXPECT_LT(b44a.exr().size(), half.exr().size() / 3);  // at most 45 of 128 bytes a block
  const std::vector<float> pixels = Pixels(b44a);
  ASSERT_EQ(pixels.size(), reference.size());
  const double psnr = SrgbPsnr(pixels.data(), reference.data(), pixels.size() / 4);
  std::printf("b44a, airport 1280x720: %zu bytes (none: %zu), PSNR %.1f dB\n", b44a.exr().size(),
              half.exr().size(), psnr);
  EXPECT_TRUE(std::isfinite(psnr)) << "b44a is lossy: the airport's frame must differ somewhere";
  EXPECT_GE(psnr, kB44aAirportPsnrDb);

  // A live stream's frames in b44a, each the same camera's frame.
  grpc::ClientContext context;
  context.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(60));
  auto stream = stub_->RenderStream(&context);
  for (uint64_t i = 0; i < 2; ++i) {
    v1::RenderFrameRequest request = request_;
    request.mutable_options()->set_compression(v1::EXR_COMPRESSION_B44A);
    request.set_frame_index(i);
    ASSERT_TRUE(stream->Write(request));
  }
  stream->WritesDone();
  const std::vector<v1::RenderFrameResponse> answers = ReadAllAnswers(*stream);
  ASSERT_TRUE(stream->Finish().ok());
  size_t rendered = 0;
  for (const v1::RenderFrameResponse& answer : answers) {
    ASSERT_EQ(answer.status_code(), 0) << answer.status_message();
    if (answer.outcome() != v1::FRAME_OUTCOME_RENDERED) continue;
    ++rendered;
    EXPECT_EQ(CompressionOf(answer.exr()), "b44a");
    const std::vector<float> streamed = Pixels(answer);
    ASSERT_EQ(streamed.size(), reference.size());
    EXPECT_GE(SrgbPsnr(streamed.data(), reference.data(), streamed.size() / 4), kB44aAirportPsnrDb);
  }
  EXPECT_GE(rendered, 1u);
}

TEST_F(NetworkCodecTest, B44AndDwabRoundTripAndFloatPixelsWithB44AreRefused) {
  const std::vector<float> reference = Pixels(RenderIn(v1::EXR_COMPRESSION_NONE));
  ASSERT_FALSE(reference.empty());
  for (v1::ExrCompression c : {v1::EXR_COMPRESSION_B44, v1::EXR_COMPRESSION_DWAB}) {
    const v1::RenderFrameResponse response = RenderIn(c);
    const std::string name = c == v1::EXR_COMPRESSION_B44 ? "b44" : "dwab";
    EXPECT_EQ(CompressionOf(response.exr()), name);
    const std::vector<float> pixels = Pixels(response);
    ASSERT_EQ(pixels.size(), reference.size()) << name;
    const double psnr = SrgbPsnr(pixels.data(), reference.data(), pixels.size() / 4);
    EXPECT_TRUE(std::isfinite(psnr)) << name << " is lossy";
    EXPECT_GE(psnr, kLossyCodecPsnrDb) << name;
  }

  v1::RenderFrameRequest request = request_;
  request.mutable_options()->set_compression(v1::EXR_COMPRESSION_B44A);
  request.mutable_options()->set_pixel_type(v1::PIXEL_TYPE_FLOAT);
  v1::RenderFrameResponse response;
  const grpc::Status refused = Render(request, 30, &response);
  EXPECT_EQ(refused.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_THAT(refused.error_message(), HasSubstr("--float-pixels"));
  EXPECT_THAT(refused.error_message(), HasSubstr("b44a"));
}

// `aperture sim` against this (loopback) server keeps zip unless --compression says otherwise.
TEST_F(NetworkCodecTest, SimOnLoopbackKeepsZipAndSendsTheCompressionNamed) {
  const std::filesystem::path dir = std::filesystem::path(::testing::TempDir()) /
                                    ("aperture_sim_codec_" + std::to_string(getpid()));
  for (const std::string compression : {"", "b44a"}) {
    std::vector<std::string> argv = {APERTURE_CLIENT_BIN,
                                     "sim",
                                     "--server=" + server_->address(),
                                     "--scene=airport",
                                     "--size=64x36",
                                     "--rate=10",
                                     "--frames=2",
                                     "--last-frames=" + dir.string()};
    if (!compression.empty()) argv.push_back("--compression=" + compression);
    const CommandResult sim = RunCommand(argv, 60);
    ASSERT_EQ(sim.exit_code, 0) << sim.err;
    std::ifstream file(dir / "channel-0.exr", std::ios::binary);
    const std::string exr((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
    EXPECT_EQ(CompressionOf(exr), compression.empty() ? "zip" : compression);
  }
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace aperture::testing
