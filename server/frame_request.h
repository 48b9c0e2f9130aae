// Validation of a RenderFrameRequest against the engine's rules and the server's limits: camera,
// options (mode included), region and pixel count become the engine's types, or an error naming
// the field.
#pragma once

#include <cstdint>

#include "absl/status/statusor.h"
#include "aperture/v1/render_service.pb.h"
#include "io/exr_writer.h"
#include "render/frame_renderer.h"
#include "render/render_options.h"
#include "scene/camera.h"

namespace aperture {

struct FrameJob {
  Camera camera;
  RenderSettings settings;  // threads = 0: the frame runs on the caller's (the server's) arena
  ExrOptions exr;
  ModeOptions mode;  // raster, or seed 003's raytrace with its options
};

absl::StatusOr<FrameJob> ParseFrameRequest(const v1::RenderFrameRequest& request,
                                           uint64_t max_pixels);

}  // namespace aperture
