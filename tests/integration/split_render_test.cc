// One frame split over two servers: PlanRegions cuts it into bands of equal predicted
// cost, `aperture render --split` renders them on both servers at once and assembles one EXR
// whose pixels equal one server's frame.
#include <gmock/gmock.h>
#include <grpcpp/grpcpp.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>
#include <vector>

#include "aperture/v1/render_service.grpc.pb.h"
#include "integration/server_process.h"
#include "integration/service_fixture.h"
#include "support/exr_pixels.h"
// After the protobuf headers: OpenImageIO's byte-swap macros break protobuf's port.h.
#include <OpenImageIO/imagebuf.h>

namespace aperture::testing {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

class SplitRenderTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::path(::testing::TempDir()) / ("aperture_split_" + std::to_string(getpid()));
    fs::create_directories(dir_);
    std::string error;
    a_ = ServerProcess::Start({"--threads=1"}, &error);
    ASSERT_NE(a_, nullptr) << error;
    b_ = ServerProcess::Start({"--threads=1"}, &error);
    ASSERT_NE(b_, nullptr) << error;
  }
  void TearDown() override { fs::remove_all(dir_); }

  CommandResult Client(std::vector<std::string> args) {
    args.insert(args.begin(), APERTURE_CLIENT_BIN);
    return RunCommand(args, 120);
  }

  fs::path dir_;
  std::unique_ptr<ServerProcess> a_, b_;
};

TEST_F(SplitRenderTest, TheAssembledFrameEqualsOneServersFrame) {
  const std::vector<std::string> frame = {"--scene=skewed", "--size=240x160", "--aa=tent2"};
  std::vector<std::string> split = {"render", "--split=3",
                                    "--servers=" + a_->address() + "," + b_->address(),
                                    "-o=" + (dir_ / "split.exr").string()};
  split.insert(split.end(), frame.begin(), frame.end());
  const CommandResult assembled = Client(split);
  ASSERT_EQ(assembled.exit_code, 0) << assembled.out << assembled.err;
  EXPECT_THAT(assembled.out, HasSubstr("split 240x160 into 3 regions over 2 servers"));
  EXPECT_THAT(assembled.out, HasSubstr("on " + a_->address()));
  EXPECT_THAT(assembled.out, HasSubstr("on " + b_->address()));

  std::vector<std::string> single = {"render", "--server=" + b_->address(),
                                     "-o=" + (dir_ / "single.exr").string()};
  single.insert(single.end(), frame.begin(), frame.end());
  const CommandResult whole = Client(single);
  ASSERT_EQ(whole.exit_code, 0) << whole.err;

  int sw = 0, sh = 0, ww = 0, wh = 0;
  const std::vector<float> p = ReadPixels((dir_ / "split.exr").string(), &sw, &sh);
  const std::vector<float> q = ReadPixels((dir_ / "single.exr").string(), &ww, &wh);
  ASSERT_FALSE(p.empty());
  EXPECT_EQ(sw, 240);
  EXPECT_EQ(sh, 160);
  ASSERT_EQ(p.size(), q.size());
  size_t differing = 0;
  for (size_t i = 0; i < p.size(); ++i) differing += p[i] != q[i];
  EXPECT_EQ(differing, 0u) << "the assembled frame differs from the single-server frame";

  // The assembled frame keeps the header every producer writes.
  auto split_file = OIIO::ImageInput::open((dir_ / "split.exr").string());
  auto single_file = OIIO::ImageInput::open((dir_ / "single.exr").string());
  ASSERT_TRUE(split_file && single_file) << OIIO::geterror();
  const OIIO::ImageSpec &split_spec = split_file->spec(), &single_spec = single_file->spec();
  for (const char* name : {"aperture:scene", "aperture:camera", "aperture:mode", "Software"}) {
    EXPECT_FALSE(single_spec.get_string_attribute(name).empty()) << name;
    EXPECT_EQ(split_spec.get_string_attribute(name), single_spec.get_string_attribute(name))
        << name;
  }
  EXPECT_EQ(split_spec.get_int_attribute("aperture:split_regions"), 3);
  EXPECT_GT(split_spec.get_float_attribute("aperture:render_ms"), 0.0f);
  EXPECT_EQ(split_spec.full_width, 240);
  EXPECT_EQ(split_spec.x, 0);
}

// A region rendered alone opens at its place in the frame: oiiotool reads its data window inside
// the whole frame's display window, and its pixels are the whole frame's there.
TEST_F(SplitRenderTest, ARegionOpensAtItsPlaceInTheFrame) {
  const std::vector<std::string> frame = {"--scene=skewed", "--size=240x160", "--aa=tent2"};
  std::vector<std::string> band = {"render", "--server=" + a_->address(), "--region=40,60,100x50",
                                   "-o=" + (dir_ / "band.exr").string()};
  band.insert(band.end(), frame.begin(), frame.end());
  const CommandResult part = Client(band);
  ASSERT_EQ(part.exit_code, 0) << part.out << part.err;
  std::vector<std::string> single = {"render", "--server=" + a_->address(),
                                     "-o=" + (dir_ / "whole.exr").string()};
  single.insert(single.end(), frame.begin(), frame.end());
  ASSERT_EQ(Client(single).exit_code, 0);

  const CommandResult info =
      RunCommand({"/usr/bin/oiiotool", "--info", "-v", (dir_ / "band.exr").string()}, 30);
  ASSERT_EQ(info.exit_code, 0) << info.err;
  EXPECT_THAT(info.out, ::testing::ContainsRegex("100 x +50, 4 channel"));
  EXPECT_THAT(info.out, HasSubstr("full/display size: 240 x 160"));
  EXPECT_THAT(info.out, HasSubstr("pixel data origin: x=40, y=60"));

  // Pasted by oiiotool over a black frame at its data window, it equals the whole frame there.
  const std::string pasted = (dir_ / "pasted.exr").string();
  const CommandResult paste =
      RunCommand({"/usr/bin/oiiotool", (dir_ / "whole.exr").string(), "--mulc", "0",
                  (dir_ / "band.exr").string(), "--over", "-o", pasted},
                 30);
  ASSERT_EQ(paste.exit_code, 0) << paste.err;
  int bw = 0, bh = 0, ww = 0, wh = 0;
  const std::vector<float> p = ReadPixels(pasted, &bw, &bh);
  const std::vector<float> q = ReadPixels((dir_ / "whole.exr").string(), &ww, &wh);
  ASSERT_EQ(bw, 240);
  ASSERT_EQ(p.size(), q.size());
  size_t differing = 0, outside = 0;
  for (int y = 0; y < 160; ++y)
    for (int x = 0; x < 240; ++x)
      for (int c = 0; c < 4; ++c) {
        const size_t i = (static_cast<size_t>(y) * 240 + x) * 4 + c;
        const bool inside = x >= 40 && x < 140 && y >= 60 && y < 110;
        if (inside)
          differing += p[i] != q[i];
        else
          outside += p[i] != 0.0f;
      }
  EXPECT_EQ(differing, 0u) << "the region's pixels are not the frame's at its place";
  EXPECT_EQ(outside, 0u) << "the region covers pixels outside its place";
}

TEST_F(SplitRenderTest, PlanRegionsTilesTheFrameAndChecksItsInput) {
  grpc::ChannelArguments args;
  auto stub = v1::Render::NewStub(
      grpc::CreateCustomChannel(a_->address(), grpc::InsecureChannelCredentials(), args));
  const v1::LoadSceneResponse loaded = LoadBuiltinScene(*stub, "demo");
  ASSERT_FALSE(loaded.scene_id().empty());
  v1::PlanRegionsRequest request;
  request.set_scene_id(loaded.scene_id());
  *request.mutable_camera() = loaded.default_camera();
  request.mutable_options()->set_width(320);
  request.mutable_options()->set_height(180);
  request.set_regions(4);
  v1::PlanRegionsResponse plan;
  {
    grpc::ClientContext context;
    const grpc::Status status = stub->PlanRegions(&context, request, &plan);
    ASSERT_TRUE(status.ok()) << status.error_message();
  }
  ASSERT_EQ(plan.regions_size(), 4);
  uint32_t y = 0;
  for (const v1::PlannedRegion& r : plan.regions()) {
    EXPECT_EQ(r.region().x(), 0u);
    EXPECT_EQ(r.region().width(), 320u);
    EXPECT_EQ(r.region().y(), y);
    EXPECT_GT(r.region().height(), 0u);
    EXPECT_GT(r.predicted_ms(), 0.0);
    y += r.region().height();
  }
  EXPECT_EQ(y, 180u);

  request.set_regions(0);
  grpc::ClientContext bad;
  grpc::Status status = stub->PlanRegions(&bad, request, &plan);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_THAT(status.error_message(), HasSubstr("regions: 0 is not in 1..180"));

  request.set_regions(2);
  request.set_scene_id(std::string(64, 'f'));
  grpc::ClientContext unknown;
  status = stub->PlanRegions(&unknown, request, &plan);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::NOT_FOUND);
}

}  // namespace
}  // namespace aperture::testing
