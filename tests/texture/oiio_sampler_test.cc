// OpenImageIO's TextureSystem as a peer filter: its options are checked, and the anisotropic 16
// bilinear peer reproduces a constant texture like the defaults do.
#include "texture/oiio_sampler.h"

#include <gtest/gtest.h>

namespace aperture {
namespace {

TEST(OiioSampler, RefusesAnisotropyBelowOneAndSamplesWithEitherOptions) {
  Image image(16, 16);
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x) image.at(x, y) = {0.25f, 0.5f, 0.75f, 1.0f};
  auto bad = OiioSampler::Create(image, "", {.anisotropic = 0});
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_NE(bad.status().message().find("anisotropic"), std::string_view::npos);
  for (const OiioOptions& options : {OiioOptions{}, OiioOptions{16, true}}) {
    auto sampler = OiioSampler::Create(image, "", options);
    ASSERT_TRUE(sampler.ok()) << sampler.status();
    // A footprint 4 x 0.25 texels, turned: a constant texture stays constant.
    const Rgba c = (*sampler)->Sample({0.3, 0.7, 0.2f, 0.1f, -0.01f, 0.02f});
    EXPECT_NEAR(c.r, 0.25f, 2e-3);
    EXPECT_NEAR(c.g, 0.5f, 2e-3);
    EXPECT_NEAR(c.b, 0.75f, 2e-3);
  }
}

}  // namespace
}  // namespace aperture
