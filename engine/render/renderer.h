// What both renderers share: the raster renderer (render/frame_renderer.h: Warnock
// subdivision and exact edge anti-aliasing, seed 002) and the ray tracer (render/trace_renderer.h,
// seed 003) take the same RenderSettings and stop test and return a RenderedFrame.
#pragma once

#include <functional>
#include <vector>

#include "absl/status/status.h"
#include "base/image.h"
#include "base/pixel_rect.h"
#include "cost/task_planner.h"
#include "cost/window_cost.h"
#include "raster/aa_filter.h"
#include "raster/warnock.h"
#include "render/polygon_shader.h"

namespace aperture {

constexpr int kMaxImageSide = 16384;
constexpr int kMaxPlanWorkers = 1024;

struct RenderSettings {
  int width = 1920, height = 1080;
  PixelRect region;  // the part of the frame to render; empty: all of it
  AntiAliasing aa = AntiAliasing::kBox2;
  ShadingOptions shading;
  WarnockOptions warnock;
  SchedulingOptions scheduling;
  int threads = 0;  // > 0: a task arena of that many threads; 0: the caller's arena
  // The sky drawn as (0, 0, 0, 0): alpha is then the coverage of what the scene draws, and the
  // colour premultiplied by it (v1::RenderOptions.transparent_sky).
  bool transparent_sky = false;
  // The frame's working memory budget in bytes (render/frame_memory.h), 0: none. Past it the
  // frame stops with RESOURCE_EXHAUSTED naming the budget.
  size_t max_frame_bytes = 0;
  // The scene's clock, seconds: which flashing light points are on (RenderFrameRequest's).
  double scene_time_s = 0;
  // Whether the scene's light points are drawn (v1::RenderOptions.hide_light_points).
  bool draw_light_points = true;
};

// Whether the frame's sky varies with direction (a scene with a time of day, drawn opaque): the
// renderers then draw over a transparent sky and composite render/sky_backdrop.h's under it.
inline bool SkyByDirection(const Scene& scene, const RenderSettings& settings) {
  return scene.sky_dome.analytic && !settings.transparent_sky;
}

// The sky the renderers draw where nothing covers a pixel: the scene's one colour, or
// transparent (a transparent sky, or one composited afterwards by direction).
inline Rgba FrameSky(const Scene& scene, const RenderSettings& settings) {
  return settings.transparent_sky || SkyByDirection(scene, settings)
             ? Rgba{0, 0, 0, 0}
             : Rgba{scene.sky.r, scene.sky.g, scene.sky.b, 1};
}

struct TaskTiming {
  PixelRect rect;
  WindowFeatures features;
  double predicted_us = 0, measured_us = 0;
};

struct FrameStats {
  double setup_ms = 0;   // projection and clipping
  double raster_ms = 0;  // planning the tasks, subdivision, coverage and shading
  double plan_ms = 0;    // of raster_ms: cutting the frame into tasks
  size_t visible_polygons = 0;
  size_t empty_leaves = 0, covered_leaves = 0, mixed_leaves = 0;
  int concurrency = 1;
  // The most the frame's working memory held (render/frame_memory.h): what its budget weighs.
  size_t peak_memory_bytes = 0;
  // Light points (render/light_pass.h): footprints drawn, those partly hidden, and the time
  // their pass took (part of raster_ms).
  // Light points' footprints drawn, and of those the ones hidden wholly and in part.
  size_t lights_drawn = 0, lights_hidden = 0, lights_partly_hidden = 0;
  double lights_ms = 0;
  std::vector<TaskTiming> tasks;  // in the order they were started

  // Sum of task times over (threads x raster time): 1 when no worker ever waits.
  double BalanceEfficiency() const;
};

struct RenderedFrame {
  Image image;       // linear RGBA of the rendered region, row 0 at its top
  PixelRect region;  // where the image lies in the frame
  FrameStats stats;
};

// Asked between tasks, between the leaf windows of a task and inside crowded cells, from worker
// threads, so it must be cheap (throttle it): true when the frame is no longer wanted (deadline,
// client cancellation, shutdown). The frame then ends with CANCELLED.
using StopRequested = std::function<bool()>;

absl::Status ValidateRenderSettings(const RenderSettings& settings);

}  // namespace aperture
