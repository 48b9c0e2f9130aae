// The scene texture's aniso / oiio / reference samplers, built on first use; a filter that
// cannot be built is an error naming it.
#include "texture/footprint_samplers.h"

#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <atomic>

#include "texture/mip_pyramid.h"

namespace aperture {
namespace {

TEST(FootprintSamplers, BuildsEachModeOnceAndRefusesTheMipMapsModes) {
  const Rgba c{0.2f, 0.4f, 0.6f, 1.0f};
  const MipPyramid pyramid(Image(64, 64, c));
  const FootprintSamplers samplers(pyramid.level(0), nullptr);
  const TextureFootprint f{0.3, 0.7, 0.25f, 0.01f, -0.02f, 0.03f};
  for (FilterMode mode : {FilterMode::kAniso, FilterMode::kOiio, FilterMode::kReference}) {
    SCOPED_TRACE(FilterModeName(mode));
    const absl::StatusOr<const TextureSampler*> s = samplers.Get(mode);
    ASSERT_TRUE(s.ok()) << s.status();
    ASSERT_NE(*s, nullptr);
    EXPECT_EQ(*s, *samplers.Get(mode));  // built once
    const Rgba got = (*s)->Sample(f);
    EXPECT_NEAR(got.r, c.r, 2e-3);  // OpenImageIO's copy is 8-bit: 51/255 = 0.2 exactly
    EXPECT_NEAR(got.b, c.b, 2e-3);
  }
  for (FilterMode mode : {FilterMode::kNearest, FilterMode::kBilinear, FilterMode::kTrilinear})
    EXPECT_FALSE(samplers.Get(mode).ok()) << FilterModeName(mode);
}

// A table that cannot be built is an error naming the filter, on this call and every later one.
TEST(FootprintSamplers, ATableThatCannotBeBuiltIsAnErrorNamingTheFilter) {
  const Image too_wide((1 << kTableMaxLog2Size) * 2, 1, Rgba{0.5f, 0.5f, 0.5f, 1});
  const FootprintSamplers samplers(too_wide, nullptr);
  for (int call = 0; call < 2; ++call) {
    const absl::StatusOr<const TextureSampler*> s = samplers.Get(FilterMode::kAniso);
    ASSERT_FALSE(s.ok());
    EXPECT_EQ(s.status().code(), absl::StatusCode::kInvalidArgument);
    EXPECT_NE(s.status().message().find("aniso filter"), std::string::npos) << s.status();
    EXPECT_NE(s.status().message().find("limit"), std::string::npos) << s.status();
  }
}

// A load whose deadline passes stops the table build; the stop is no answer,
// so the next caller (with no stop) builds the table after all.
TEST(FootprintSamplers, AStoppedTableBuildIsCancelledAndBuiltByTheNextCaller) {
  const MipPyramid pyramid(Image(256, 256, Rgba{0.5f, 0.5f, 0.5f, 1}));
  const FootprintSamplers samplers(pyramid.level(0), nullptr);
  std::atomic<int> asked{0};  // asked from the builder's worker threads too
  const absl::Status stopped = samplers.PrepareAniso([&] { return ++asked >= 3; });
  EXPECT_TRUE(absl::IsCancelled(stopped)) << stopped;
  // Stopped at the first "yes": threads that asked at the same moment may add one each.
  EXPECT_GE(asked.load(), 3);
  EXPECT_LE(asked.load(), 3 + tbb::this_task_arena::max_concurrency());
  EXPECT_TRUE(samplers.PrepareAniso().ok());
  const absl::StatusOr<const TextureSampler*> aniso = samplers.Get(FilterMode::kAniso);
  ASSERT_TRUE(aniso.ok()) << aniso.status();
  EXPECT_NE(*aniso, nullptr);
}

}  // namespace
}  // namespace aperture
