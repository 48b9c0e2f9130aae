#include "render/render_options.h"

#include "absl/strings/str_cat.h"
#include "scene/scene_builder.h"

namespace aperture {
namespace {

absl::Status SideError(const char* field, uint32_t value) {
  return absl::InvalidArgumentError(
      absl::StrCat("options.", field, " is ", value, "; must be 1..", kMaxImageSide));
}

}  // namespace

absl::StatusOr<RenderSettings> RenderSettingsFromProto(const v1::RenderOptions& options) {
  RenderSettings settings;
  if (options.width() < 1 || options.width() > kMaxImageSide)
    return SideError("width", options.width());
  if (options.height() < 1 || options.height() > kMaxImageSide)
    return SideError("height", options.height());
  settings.width = static_cast<int>(options.width());
  settings.height = static_cast<int>(options.height());

  switch (options.anti_aliasing()) {
    case v1::ANTI_ALIASING_DEFAULT:
    case v1::ANTI_ALIASING_BOX2:
      settings.aa = AntiAliasing::kBox2;
      break;
    case v1::ANTI_ALIASING_BOX1:
      settings.aa = AntiAliasing::kBox1;
      break;
    case v1::ANTI_ALIASING_TENT2:
      settings.aa = AntiAliasing::kTent2;
      break;
    default:
      return absl::InvalidArgumentError(
          absl::StrCat("options.anti_aliasing has unknown value ", options.anti_aliasing()));
  }

  settings.shading.override_filter = options.filter() != v1::TEXTURE_FILTER_DEFAULT;
  if (settings.shading.override_filter) {
    const std::optional<FilterMode> filter = FilterModeFromProto(options.filter());
    if (!filter)
      return absl::InvalidArgumentError(
          absl::StrCat("options.filter has unknown value ", options.filter()));
    settings.shading.filter = *filter;
  }

  if (options.texture_aperture() != 0) {
    settings.shading.texture_aperture = options.texture_aperture();
    if (auto s = ValidateRenderSettings(settings); !s.ok())
      return absl::InvalidArgumentError(absl::StrCat("options.texture_aperture is ",
                                                     options.texture_aperture(),
                                                     "; must be in (0, 16] pixels"));
  }
  settings.transparent_sky = options.transparent_sky();
  return settings;
}

absl::StatusOr<ExrOptions> ExrOptionsFromProto(const v1::RenderOptions& options) {
  ExrOptions exr;
  switch (options.pixel_type()) {
    case v1::PIXEL_TYPE_DEFAULT:
    case v1::PIXEL_TYPE_HALF:
      exr.pixel_type = ExrPixelType::kHalf;
      break;
    case v1::PIXEL_TYPE_FLOAT:
      exr.pixel_type = ExrPixelType::kFloat;
      break;
    default:
      return absl::InvalidArgumentError(
          absl::StrCat("options.pixel_type has unknown value ", options.pixel_type()));
  }
  switch (options.compression()) {
    case v1::EXR_COMPRESSION_DEFAULT:
    case v1::EXR_COMPRESSION_ZIP:
      exr.compression = ExrCompression::kZip;
      break;
    case v1::EXR_COMPRESSION_NONE:
      exr.compression = ExrCompression::kNone;
      break;
    case v1::EXR_COMPRESSION_RLE:
      exr.compression = ExrCompression::kRle;
      break;
    case v1::EXR_COMPRESSION_ZIPS:
      exr.compression = ExrCompression::kZips;
      break;
    case v1::EXR_COMPRESSION_PIZ:
      exr.compression = ExrCompression::kPiz;
      break;
    case v1::EXR_COMPRESSION_DWAA:
      exr.compression = ExrCompression::kDwaa;
      break;
    default:
      return absl::InvalidArgumentError(
          absl::StrCat("options.compression has unknown value ", options.compression()));
  }
  return exr;
}

}  // namespace aperture
