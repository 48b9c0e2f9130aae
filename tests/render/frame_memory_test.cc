// A frame's working memory against its budget (render/frame_memory.h): the holders' bytes add up,
// passing the budget sticks, and a frame stops with RESOURCE_EXHAUSTED naming its budget exactly
// where its working memory would pass it, at every stage (the image, the projected polygons, the
// workers' buffers), while a frame within its budget is the frame without one.
#include "render/frame_memory.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "render/frame_renderer.h"
#include "scene/scene_builder.h"
#include "support/hostile_scenes.h"

namespace aperture {
namespace {

using ::testing::HasSubstr;

TEST(FrameMemory, HoldersAddUpAndPassingTheBudgetSticks) {
  FrameMemory memory(1000);
  size_t a = 0, b = 0;
  EXPECT_TRUE(memory.Hold(a, 400));
  EXPECT_TRUE(memory.Hold(b, 500));
  EXPECT_EQ(memory.Room(), 100u);
  EXPECT_TRUE(memory.Hold(a, 100));  // a release
  EXPECT_EQ(memory.Room(), 400u);
  EXPECT_FALSE(memory.Hold(b, 950));
  EXPECT_TRUE(memory.Exceeded());
  EXPECT_FALSE(memory.Hold(b, 0));  // once passed, the frame is over
  EXPECT_EQ(memory.Error().code(), absl::StatusCode::kResourceExhausted);
  EXPECT_THAT(std::string(memory.Error().message()), HasSubstr("budget of 1 MiB"));
  FrameMemory unlimited(0);
  EXPECT_TRUE(unlimited.Hold(a, size_t{1} << 50));
  EXPECT_EQ(unlimited.Room(), SIZE_MAX);
}

class FrameBudgetTest : public ::testing::Test {
 protected:
  void SetUp() override {
    auto built = BuildScene(testing::CoplanarCrowdScene(false));
    ASSERT_TRUE(built.ok()) << built.status();
    scene_ = *std::move(built);
    camera_.vertical_fov_deg = 60;
    settings_.width = 320;
    settings_.height = 240;
    settings_.threads = 1;  // the holds then come in one order: the peak is repeatable
  }
  Scene scene_;
  Camera camera_;
  RenderSettings settings_;
};

TEST_F(FrameBudgetTest, AFrameStopsWhereItsWorkingMemoryWouldPassTheBudget) {
  auto unlimited = RenderFrame(scene_, camera_, settings_);
  ASSERT_TRUE(unlimited.ok()) << unlimited.status();
  const size_t peak = unlimited->stats.peak_memory_bytes;
  const size_t image = size_t{320} * 240 * sizeof(Rgba);
  // The workers' buffers come last, above the image and the projected polygons.
  ASSERT_GT(peak, image + scene_.polygons.size() * sizeof(ScreenPolygon));

  settings_.max_frame_bytes = peak;
  auto within = RenderFrame(scene_, camera_, settings_);
  ASSERT_TRUE(within.ok()) << within.status();
  EXPECT_EQ(within->stats.peak_memory_bytes, peak);
  for (int y = 0; y < settings_.height; ++y)
    for (int x = 0; x < settings_.width; ++x)
      ASSERT_EQ(within->image.at(x, y), unlimited->image.at(x, y)) << x << "," << y;

  settings_.max_frame_bytes = peak - 1;
  auto over = RenderFrame(scene_, camera_, settings_);
  ASSERT_EQ(over.status().code(), absl::StatusCode::kResourceExhausted) << over.status();
  EXPECT_THAT(std::string(over.status().message()), HasSubstr("--max-frame-mb"));

  settings_.max_frame_bytes = image - 1;  // the image alone does not fit: refused before
  auto no_image = RenderFrame(scene_, camera_, settings_);
  ASSERT_EQ(no_image.status().code(), absl::StatusCode::kResourceExhausted);
  EXPECT_THAT(std::string(no_image.status().message()), HasSubstr("the image"));

  settings_.max_frame_bytes = image + 1000;  // nor the projected polygons
  auto no_polygons = RenderFrame(scene_, camera_, settings_);
  ASSERT_EQ(no_polygons.status().code(), absl::StatusCode::kResourceExhausted);
  EXPECT_THAT(std::string(no_polygons.status().message()), HasSubstr("projected polygons"));
}

}  // namespace
}  // namespace aperture
