// A frame request (aperture.v1.RenderFrameRequest) as the engine's job: camera, render settings
// (region included), EXR options and render mode, validated, or an error naming the field. The
// one conversion the server and aperture-render share, so that a frame asked of either is the
// same frame.
#pragma once

#include "absl/status/statusor.h"
#include "aperture/v1/render_service.pb.h"
#include "frame/render_options_proto.h"
#include "io/exr_writer.h"
#include "render/renderer.h"
#include "scene/camera.h"

namespace aperture {

struct FrameJob {
  Camera camera;
  RenderSettings settings;  // threads = 0: the caller's arena
  ExrOptions exr;
  ModeOptions mode;  // raster, or seed 003's raytrace with its options
};

absl::StatusOr<FrameJob> FrameJobFromRequest(const v1::RenderFrameRequest& request);

}  // namespace aperture
