// The proto's render options (aperture.v1.RenderOptions) as the engine's settings: what to render
// (RenderSettings) and with which renderer (ModeOptions). How to encode it is
// frame/exr_options_proto.h's. Errors name the offending field.
#pragma once

#include "absl/status/statusor.h"
#include "aperture/v1/scene.pb.h"
#include "render/renderer.h"
#include "render/trace_renderer.h"

namespace aperture {

// Size, edge anti-aliasing, texture filter override and aperture; `threads` is left at 0 (the
// caller's arena) and `region` empty (the whole frame).
// Width and height are required (1..kMaxImageSide); texture_aperture 0 means the default, 2.
absl::StatusOr<RenderSettings> RenderSettingsFromProto(const v1::RenderOptions& options);

// The render mode (options.mode) and, for seed 003's raytrace mode, its options.
struct ModeOptions {
  bool raytrace = false;  // DEFAULT and RASTER: the Warnock rasterizer
  TraceOptions trace;     // delta (0: 0.1) and max_depth (unset: 3)
};

absl::StatusOr<ModeOptions> ModeOptionsFromProto(const v1::RenderOptions& options);

}  // namespace aperture
