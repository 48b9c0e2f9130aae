// The channels `aperture sim --channels SPEC` runs: planar tiles, rings of channels turned around
// the eye, channel-set files; bad input named.
#include "sim_channels.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>

namespace aperture {
namespace {

using ::testing::HasSubstr;

double Degrees(double radians) { return radians * 180 / M_PI; }

TEST(SimChannels, ARingOfThreeSixtiesSpansOneHundredAndEightyDegrees) {
  auto channels = ParseChannels("3x60", v1::Camera(), 640, 480);
  ASSERT_TRUE(channels.ok()) << channels.status();
  ASSERT_EQ(channels->size(), 3u);
  const double yaws[] = {60, 0, -60};  // left to right: positive yaw turns left
  for (size_t k = 0; k < 3; ++k) {
    const SimChannel& c = (*channels)[k];
    EXPECT_EQ(c.view_offset.yaw_deg(), yaws[k]);
    EXPECT_EQ(c.frustum.left_deg(), -30);
    EXPECT_EQ(c.frustum.right_deg(), 30);
    // Square pixels: tan(top) / tan(right) = 480 / 640.
    EXPECT_NEAR(c.frustum.top_deg(), Degrees(std::atan(std::tan(M_PI / 6) * 0.75)), 1e-12);
    EXPECT_EQ(c.frustum.bottom_deg(), -c.frustum.top_deg());
    EXPECT_EQ(c.width, 640u);
  }
  // Five of 36: the middle one looks ahead, the outer ones 72 degrees off.
  channels = ParseChannels("5x36x40", v1::Camera(), 640, 480);
  ASSERT_TRUE(channels.ok()) << channels.status();
  EXPECT_EQ((*channels)[0].view_offset.yaw_deg(), 72);
  EXPECT_EQ((*channels)[2].view_offset.yaw_deg(), 0);
  EXPECT_EQ((*channels)[4].view_offset.yaw_deg(), -72);
  EXPECT_EQ((*channels)[4].frustum.top_deg(), 20);
}

TEST(SimChannels, PlanarTilesKeepTheEyesViewForOneChannel) {
  v1::Camera eye;
  eye.set_vertical_fov_deg(40);
  auto one = ParseChannels("1", eye, 64, 40);
  ASSERT_TRUE(one.ok()) << one.status();
  EXPECT_FALSE((*one)[0].has_frustum);
  EXPECT_EQ(ChannelCamera(eye, (*one)[0]).vertical_fov_deg(), 40);
  auto three = ParseChannels("3", eye, 64, 40);
  ASSERT_TRUE(three.ok()) << three.status();
  // Three tiles each 2 tan 20 * 64 / 40 wide: the outer edges at atan(3 tan 20 * 64 / 40).
  const double half = 3 * std::tan(M_PI / 9) * 64 / 40;
  EXPECT_NEAR((*three)[0].frustum.left_deg(), -Degrees(std::atan(half)), 1e-12);
  EXPECT_NEAR((*three)[2].frustum.right_deg(), Degrees(std::atan(half)), 1e-12);
  EXPECT_EQ((*three)[0].frustum.right_deg(), (*three)[1].frustum.left_deg());
}

TEST(SimChannels, TheExampleFileIsAHundredAndEightyByForty) {
  auto channels = ParseChannels(APERTURE_EXAMPLES_DIR "/wrap-180x40.txtpb", v1::Camera(), 64, 40);
  ASSERT_TRUE(channels.ok()) << channels.status();
  ASSERT_EQ(channels->size(), 3u);
  EXPECT_EQ((*channels)[0].name, "left");
  double left = 1e9, right = -1e9;
  for (const SimChannel& c : *channels) {
    left = std::min(left, -c.view_offset.yaw_deg() + c.frustum.left_deg());
    right = std::max(right, -c.view_offset.yaw_deg() + c.frustum.right_deg());
    // The frustum's top edge at its sides (30 degrees off axis) still reaches 20 degrees up.
    const double side_top = Degrees(std::atan(std::tan(c.frustum.top_deg() * M_PI / 180) *
                                              std::cos(c.frustum.right_deg() * M_PI / 180)));
    EXPECT_GE(side_top, 20);
    EXPECT_EQ(c.width, 640u);  // the file's size, not --size
  }
  EXPECT_EQ(right - left, 180);
}

TEST(SimChannels, ServersAreTheChannelsOwnThenRoundRobinThenTheDefault) {
  auto channels = ParseChannels("3x60", v1::Camera(), 64, 40);
  ASSERT_TRUE(channels.ok());
  (*channels)[1].server = "own:1";
  AssignServers(*channels, {"a:1", "b:1"}, "default:1");
  EXPECT_EQ((*channels)[0].server, "a:1");
  EXPECT_EQ((*channels)[1].server, "own:1");
  EXPECT_EQ((*channels)[2].server, "a:1");
  auto alone = ParseChannels("2x60", v1::Camera(), 64, 40);
  ASSERT_TRUE(alone.ok());
  AssignServers(*alone, {}, "default:1");
  EXPECT_EQ((*alone)[1].server, "default:1");
}

TEST(SimChannels, BadInputIsNamed) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("sim_channels_test_" + std::to_string(getpid()));
  std::filesystem::create_directories(dir);
  auto error_of = [&](const std::string& spec, const std::string& file_text = "") {
    std::string argument = spec;
    if (!file_text.empty()) {
      argument = (dir / spec).string();
      std::ofstream(argument) << file_text;
    }
    auto channels = ParseChannels(argument, v1::Camera(), 64, 40);
    EXPECT_FALSE(channels.ok()) << spec;
    return std::string(channels.status().message());
  };
  EXPECT_THAT(error_of("17"), HasSubstr("1..16"));
  EXPECT_THAT(error_of("3x200"), HasSubstr("channel width is 200"));
  EXPECT_THAT(error_of("5x90"), HasSubstr("total width is 450"));
  EXPECT_THAT(error_of("nosuchfile"), HasSubstr("neither N, NxW, NxWxV nor a readable"));
  EXPECT_THAT(error_of("a.txtpb", "channels { nmae: \"x\" }"), HasSubstr("a.txtpb:1:"));
  EXPECT_THAT(error_of("b.txtpb", "channels { name: \"x\" }"),
              HasSubstr("channels[0].horizontal_fov_deg or frustum"));
  EXPECT_THAT(error_of("c.txtpb",
                       "channels { horizontal_fov_deg: 60 }\n"
                       "channels { frustum { left_deg: 10 right_deg: -10 top_deg: 1 } }"),
              HasSubstr("channels[1].frustum.left_deg is 10"));
  EXPECT_THAT(error_of("d.txtpb", "channels { horizontal_fov_deg: 190 }"),
              HasSubstr("channels[0].horizontal_fov_deg is 190"));
  EXPECT_THAT(error_of("e.txtpb", "# nothing\n"), HasSubstr("the number of channels is 0"));
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace aperture
