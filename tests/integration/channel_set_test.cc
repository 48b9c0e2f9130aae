// A channel set around the eye on three servers: `aperture sim --channels
// docs/examples/wrap-180x40.txtpb --servers A,B,C` renders each of the three 60-degree channels on
// its own server, every frame number on all three; the last frames, of a dome of black and white
// 5-degree squares around the eye, show each square where its analytic direction says, and the
// channels meet at their seams (on a square's edge) with neither gap nor overlap: with the 2 x 2
// box filter, each of the seam's two columns is 3/4 its own square and 1/4 the next one's.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

// clang-format off
#include <google/protobuf/text_format.h>
#include <google/protobuf/util/json_util.h>
#include "aperture/v1/channel_set.pb.h"
#include "aperture/v1/client_reports.pb.h"
// clang-format on
#include "integration/server_process.h"
#include "support/checker_dome.h"
#include "support/exr_pixels.h"
// After the protobuf headers: OpenImageIO's byte-swap macros break protobuf's port.h.
#include <OpenImageIO/imagebuf.h>

namespace aperture::testing {
namespace {

namespace fs = std::filesystem;

TEST(ChannelSetTest, ThreeServersRenderOneFrameNumberWithSeamlessSeams) {
  const fs::path dir =
      fs::path(::testing::TempDir()) / ("aperture_channel_set_" + std::to_string(getpid()));
  fs::create_directories(dir);
  std::vector<std::unique_ptr<ServerProcess>> servers;
  std::string addresses, error;
  for (int k = 0; k < 3; ++k) {
    servers.push_back(ServerProcess::Start({"--threads=1"}, &error));
    ASSERT_NE(servers.back(), nullptr) << error;
    addresses += (k ? "," : "") + servers.back()->address();
  }
  std::string scene_json;
  ASSERT_TRUE(google::protobuf::util::MessageToJsonString(CheckerDome(), &scene_json).ok());
  std::ofstream(dir / "dome.json") << scene_json;
  std::ofstream(dir / "still.path") << "0,0,0,0,0,0\n0,0,0,0,0,0\n0,0,0,0,0,0\n";
  const std::string set_file = APERTURE_EXAMPLES_DIR "/wrap-180x40.txtpb";
  const fs::path last = dir / "last";
  const CommandResult result =
      RunCommand({APERTURE_CLIENT_BIN, "sim", "--scene=" + (dir / "dome.json").string(),
                  "--path=" + (dir / "still.path").string(), "--channels=" + set_file,
                  "--servers=" + addresses, "--rate=4", "--aa=box2", "--float_pixels",
                  "--last_frames=" + last.string(), "--json"},
                 120);
  ASSERT_EQ(result.exit_code, 0) << result.out << result.err;
  v1::SimReport report;
  ASSERT_TRUE(google::protobuf::util::JsonStringToMessage(result.out, &report).ok()) << result.out;

  // Each channel on its own server, every frame number rendered on all three.
  ASSERT_EQ(report.channels_size(), 3);
  for (int k = 0; k < 3; ++k) {
    const v1::SimChannelReport& c = report.channels(k);
    EXPECT_EQ(c.server(), servers[k]->address());
    EXPECT_EQ(c.ok(), 3u) << c.name();
    EXPECT_EQ(c.last_frame(), 2u) << c.name();  // the written frames: one frame number
    // Its own transport delay: rendered, so more than nothing, and ordered.
    EXPECT_GT(c.transport_delay_ms().p50(), 0) << c.name();
    EXPECT_LE(c.transport_delay_ms().p50(), c.transport_delay_ms().max()) << c.name();
    EXPECT_GT(c.transport_delay_ms().render(), 0) << c.name();
  }
  EXPECT_EQ(report.channels(0).name(), "left");
  EXPECT_EQ(report.locked_frames(), 3u);
  EXPECT_GE(report.channel_skew_ms().max(), report.channel_skew_ms().p50());
  EXPECT_GE(report.channel_skew_ms().p50(), 0);

  // The frames against the dome, through the channel set's own definition.
  v1::ChannelSet set;
  std::ifstream in(set_file);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_TRUE(google::protobuf::TextFormat::ParseFromString(text, &set));
  std::vector<ChannelView> views;
  std::vector<std::vector<float>> frames;
  size_t checked = 0, wrong = 0;
  for (int k = 0; k < 3; ++k) {
    const v1::DisplayChannel& c = set.channels(k);
    views.emplace_back(c.view_offset().yaw_deg(), c.frustum(), static_cast<int>(c.width()),
                       static_cast<int>(c.height()));
    int w = 0, h = 0;
    frames.push_back(
        ReadPixels((last / ("channel-" + std::to_string(k) + ".exr")).string(), &w, &h));
    ASSERT_EQ(w, views[k].width);
    ASSERT_EQ(h, views[k].height);
    // Pixels well inside a square (a quarter degree, about two pixels, from its edges) show it.
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const auto [a, e] = DomeAngles(views[k].At(x + 0.5, y + 0.5));
        if (!InsideSquare(a, 0.25) || !InsideSquare(e, 0.25)) continue;
        ++checked;
        const float value = frames[k][(static_cast<size_t>(y) * w + x) * 4];
        wrong += std::abs(value - (DomeWhite(a, e) ? 1.0f : 0.0f)) > 1e-4f;
      }
  }
  EXPECT_EQ(wrong, 0u) << "of " << checked;
  // The seams at azimuth 30 and -30, each on a square's edge: the 2 x 2 box of the last column
  // of a channel reaches half a pixel into the next square, as does the first of the next.
  double worst = 0;
  size_t rows = 0;
  for (int k = 0; k + 1 < 3; ++k) {
    const int w = views[k].width;
    for (int y = 0; y < views[k].height; ++y) {
      const auto [a, e] = DomeAngles(views[k].At(w, y + 0.5));
      if (!InsideSquare(e, 0.25)) continue;
      ++rows;
      const double own = DomeWhite(a + 1, e) ? 1 : 0, next = 1 - own;
      const float left = frames[k][(static_cast<size_t>(y) * w + w - 1) * 4];
      const float right = frames[k + 1][static_cast<size_t>(y) * views[k + 1].width * 4];
      worst = std::max({worst, std::abs(left - (0.75 * own + 0.25 * next)),
                        std::abs(right - (0.75 * next + 0.25 * own))});
    }
  }
  EXPECT_GT(rows, 800u);
  EXPECT_LT(worst, 1e-4);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace aperture::testing
