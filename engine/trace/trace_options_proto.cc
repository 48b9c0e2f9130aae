#include "trace/trace_options_proto.h"

#include <cmath>

#include "absl/strings/str_cat.h"

namespace aperture {

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
