// A frame request (aperture.v1.RenderFrameRequest) as the engine's job: camera, render settings
// (region included), EXR options and render mode, validated, or an error naming the field. The
// one conversion the server and aperture-render share, so that a frame asked of either is the
// same frame; what the rendering process decides for itself (threads, budgets, tuning) comes in
// as FrameJobOptions, set before the conversion rather than patched into its job after it.
#pragma once

#include "absl/status/statusor.h"
#include "aperture/v1/render_service.pb.h"
#include "frame/render_options_proto.h"
#include "io/exr_writer.h"
#include "render/renderer.h"
#include "scene/camera.h"

namespace aperture {

// What the process rendering the frame decides, not the request: its threads and budget, the
// renderers' tuning, the encoder's effort. The defaults are the server's.
struct FrameJobOptions {
  int threads = 0;             // > 0: a task arena of that many, for rendering and encoding
  size_t max_frame_bytes = 0;  // the frame's working memory budget (render/frame_memory.h), 0: none
  WarnockOptions warnock;      // the subdivision's leaf sizes
  Scheduling scheduling = Scheduling::kCost;
  int uniform_tile = SchedulingOptions{}.uniform_tile;  // Scheduling::kUniform's tile side
  int zip_level = ExrOptions{}.zip_level;               // zip and zips deflate level, 1..9
  // Raytrace: the largest exact projection integral, in row or column steps (FragmentOptions).
  int exact_steps = FragmentOptions{}.exact_steps;
};

struct FrameJob {
  Camera camera;
  RenderSettings settings;  // threads from FrameJobOptions, 0: the caller's arena
  ExrOptions exr;
  ModeOptions mode;  // raster, or seed 003's raytrace with its options
};

// The request's job with `local`'s choices in it; the settings are validated as a whole
// (ValidateRenderSettings) and a bad local option is INVALID_ARGUMENT naming it.
absl::StatusOr<FrameJob> FrameJobFromRequest(const v1::RenderFrameRequest& request,
                                             const FrameJobOptions& local = {});

}  // namespace aperture
