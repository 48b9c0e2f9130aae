#include "frame/render_options_proto.h"

#include <cmath>

#include "absl/strings/str_cat.h"
#include "scene/scene_textures.h"

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
  settings.draw_light_points = !options.hide_light_points();
  return settings;
}

absl::StatusOr<ModeOptions> ModeOptionsFromProto(const v1::RenderOptions& options) {
  ModeOptions m;
  switch (options.mode()) {
    case v1::RENDER_MODE_DEFAULT:
    case v1::RENDER_MODE_RASTER:
      break;
    case v1::RENDER_MODE_RAYTRACE:
      m.raytrace = true;
      break;
    default:
      return absl::InvalidArgumentError(
          absl::StrCat("options.mode has unknown value ", options.mode()));
  }
  if (options.raytrace_delta() != 0) {
    if (!(options.raytrace_delta() > 0) || !std::isfinite(options.raytrace_delta()))
      return absl::InvalidArgumentError(absl::StrCat("options.raytrace_delta is ",
                                                     options.raytrace_delta(),
                                                     "; must be a positive number (0: 0.1)"));
    m.trace.fragments.delta = options.raytrace_delta();
  }
  if (options.has_raytrace_max_depth()) {
    if (options.raytrace_max_depth().value() > 8)
      return absl::InvalidArgumentError(absl::StrCat("options.raytrace_max_depth is ",
                                                     options.raytrace_max_depth().value(),
                                                     "; must be 0..8"));
    m.trace.max_depth = static_cast<int>(options.raytrace_max_depth().value());
  }
  return m;
}

}  // namespace aperture
