// v1::RenderOptions -> RenderSettings and ExrOptions: defaults, every enum value, and errors that
// name the field.
#include "frame/render_options_proto.h"

#include <gtest/gtest.h>

#include <string>

#include "frame/exr_options_proto.h"

namespace aperture {
namespace {

// The error message of `status`, which must not be OK.
std::string ErrorOf(const absl::Status& status) {
  EXPECT_FALSE(status.ok());
  return std::string(status.message());
}

#define EXPECT_NAMES(status, field) \
  EXPECT_NE(ErrorOf(status).find(field), std::string::npos) << ErrorOf(status)

v1::RenderOptions Options(uint32_t width, uint32_t height) {
  v1::RenderOptions options;
  options.set_width(width);
  options.set_height(height);
  return options;
}

TEST(RenderOptionsTest, DefaultsMatchApertureRender) {
  auto settings = RenderSettingsFromProto(Options(640, 480));
  ASSERT_TRUE(settings.ok()) << settings.status();
  EXPECT_EQ(settings->width, 640);
  EXPECT_EQ(settings->height, 480);
  EXPECT_EQ(settings->aa, AntiAliasing::kBox2);
  EXPECT_FALSE(settings->shading.override_filter);
  EXPECT_EQ(settings->shading.texture_aperture, 2.0);
  EXPECT_EQ(settings->threads, 0);
  EXPECT_EQ(settings->region.pixels(), 0);

  auto exr = ExrOptionsFromProto(Options(640, 480));
  ASSERT_TRUE(exr.ok());
  EXPECT_EQ(exr->pixel_type, ExrPixelType::kHalf);
  EXPECT_EQ(exr->compression, ExrCompression::kZip);
}

TEST(RenderOptionsTest, MapsEveryValue) {
  v1::RenderOptions options = Options(8, 8);
  options.set_anti_aliasing(v1::ANTI_ALIASING_TENT2);
  options.set_filter(v1::TEXTURE_FILTER_NEAREST);
  options.set_texture_aperture(1);
  options.set_pixel_type(v1::PIXEL_TYPE_FLOAT);
  options.set_compression(v1::EXR_COMPRESSION_PIZ);
  auto settings = RenderSettingsFromProto(options);
  ASSERT_TRUE(settings.ok());
  EXPECT_EQ(settings->aa, AntiAliasing::kTent2);
  EXPECT_TRUE(settings->shading.override_filter);
  EXPECT_EQ(settings->shading.filter, FilterMode::kNearest);
  EXPECT_EQ(settings->shading.texture_aperture, 1.0);
  auto exr = ExrOptionsFromProto(options);
  ASSERT_TRUE(exr.ok());
  EXPECT_EQ(exr->pixel_type, ExrPixelType::kFloat);
  EXPECT_EQ(exr->compression, ExrCompression::kPiz);
}

TEST(RenderOptionsTest, ErrorsNameTheField) {
  EXPECT_NAMES(RenderSettingsFromProto(Options(0, 8)).status(), "options.width");
  EXPECT_NAMES(RenderSettingsFromProto(Options(8, kMaxImageSide + 1)).status(), "options.height");

  v1::RenderOptions bad_aa = Options(8, 8);
  bad_aa.set_anti_aliasing(static_cast<v1::AntiAliasing>(99));
  EXPECT_NAMES(RenderSettingsFromProto(bad_aa).status(), "options.anti_aliasing");

  v1::RenderOptions bad_aperture = Options(8, 8);
  bad_aperture.set_texture_aperture(-1);
  EXPECT_NAMES(RenderSettingsFromProto(bad_aperture).status(), "options.texture_aperture");

  v1::RenderOptions bad_compression = Options(8, 8);
  bad_compression.set_compression(static_cast<v1::ExrCompression>(42));
  EXPECT_EQ(ExrOptionsFromProto(bad_compression).status().code(),
            absl::StatusCode::kInvalidArgument);
}

// b44 and b44a compress half channels only: float pixels with them are refused, naming the pixel
// type (and its flag) and the compression, never sent as half. dwab takes float channels.
TEST(RenderOptionsTest, FloatPixelsWithB44AreRefused) {
  v1::RenderOptions options = Options(8, 8);
  options.set_pixel_type(v1::PIXEL_TYPE_FLOAT);
  for (v1::ExrCompression c : {v1::EXR_COMPRESSION_B44, v1::EXR_COMPRESSION_B44A}) {
    options.set_compression(c);
    const absl::Status status = ExrOptionsFromProto(options).status();
    EXPECT_EQ(status.code(), absl::StatusCode::kInvalidArgument);
    EXPECT_NAMES(status, "options.pixel_type");
    EXPECT_NAMES(status, "--float-pixels");
    EXPECT_NAMES(status, c == v1::EXR_COMPRESSION_B44 ? "compression b44" : "compression b44a");
  }
  options.set_compression(v1::EXR_COMPRESSION_DWAB);
  auto dwab = ExrOptionsFromProto(options);
  ASSERT_TRUE(dwab.ok()) << dwab.status();
  EXPECT_EQ(dwab->compression, ExrCompression::kDwab);
  options.set_pixel_type(v1::PIXEL_TYPE_HALF);
  options.set_compression(v1::EXR_COMPRESSION_B44A);
  auto b44a = ExrOptionsFromProto(options);
  ASSERT_TRUE(b44a.ok()) << b44a.status();
  EXPECT_EQ(b44a->compression, ExrCompression::kB44a);
}

}  // namespace
}  // namespace aperture
