// The engine's one entry for a frame: a scene and the job made from a frame request
// (frame/frame_job.h) to the frame, by the raster renderer (render/frame_renderer.h: Warnock
// subdivision, seed 002's exact edge anti-aliasing) or seed 003's ray tracer
// (render/trace_renderer.h), as the job's mode says. The server and aperture-render both render
// through it, so the two cannot choose a renderer, or call one, differently.
#pragma once

#include <functional>
#include <memory>
#include <string>

#include "absl/status/statusor.h"
#include "frame/frame_job.h"
#include "io/exr_header.h"
#include "render/renderer.h"
#include "render/trace_renderer.h"
#include "scene/scene.h"

namespace aperture {

// Where a raytraced frame gets its scene's ray-tracing state (Embree BVH, summed-area tables),
// which costs far more than a frame and so is built once per scene by the caller and kept (the
// server's cache, aperture-render's one build). Asked once per raytraced frame, never for a raster
// one; the TracedScene must be the frame's scene's. Its error is the frame's.
using TracedSceneSource = std::function<absl::StatusOr<std::shared_ptr<const TracedScene>>()>;

// Renders `job` of `scene`: job.settings.region of the frame (empty: all of it), on
// job.settings.threads threads (0: the caller's arena). A raytraced job without a `traced` source
// builds the scene's TracedScene for this frame alone (no store). `stop` is asked as the
// renderers ask it (a frame stopped ends with CANCELLED); `trace_stats`, when given, receives a
// raytraced frame's ray and fragment counts.
absl::StatusOr<RenderedFrame> RenderFrameJob(const Scene& scene, const FrameJob& job,
                                             const TracedSceneSource& traced = {},
                                             const StopRequested& stop = {},
                                             TraceStats* trace_stats = nullptr);

// "raster" or "raytrace", as the EXR header and the logs name a job's mode.
const char* FrameJobModeName(const FrameJob& job);

// The EXR header of `frame`, rendered for `job` of the scene named `scene_name`.
ExrMetadata FrameJobMetadata(const std::string& scene_name, const FrameJob& job,
                             const RenderedFrame& frame);

}  // namespace aperture
