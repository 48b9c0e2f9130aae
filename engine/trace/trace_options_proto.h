// The render mode of a request (aperture.v1.RenderOptions.mode) and, for seed 003's raytrace
// mode, its options; errors name the offending field.
#pragma once

#include "absl/status/statusor.h"
#include "aperture/v1/scene.pb.h"
#include "trace/trace_renderer.h"

namespace aperture {

struct ModeOptions {
  bool raytrace = false;  // DEFAULT and RASTER: the Warnock rasterizer
  TraceOptions trace;     // delta (0: 0.1) and max_depth (unset: 3)
};

absl::StatusOr<ModeOptions> ModeOptionsFromProto(const v1::RenderOptions& options);

}  // namespace aperture
