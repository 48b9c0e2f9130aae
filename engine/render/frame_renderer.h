// The frame pipeline: project the scene, subdivide the screen Warnock-style, and render the leaf
// windows on oneTBB workers with exact analytic edge anti-aliasing (seed 002, eq. 2).
#pragma once

#include "absl/status/statusor.h"
#include "raster/aa_filter.h"
#include "raster/warnock.h"
#include "render/polygon_shader.h"
#include "scene/camera.h"
#include "scene/scene.h"
#include "texture/image.h"

namespace aperture {

constexpr int kMaxImageSide = 16384;

struct RenderSettings {
  int width = 1920, height = 1080;
  AntiAliasing aa = AntiAliasing::kBox2;
  ShadingOptions shading;
  WarnockOptions warnock;
  int threads = 0;  // 0: all cores
};

struct FrameStats {
  double setup_ms = 0;   // projection and clipping
  double raster_ms = 0;  // subdivision, coverage and shading
  size_t visible_polygons = 0;
  size_t empty_leaves = 0, covered_leaves = 0, mixed_leaves = 0;
};

struct RenderedFrame {
  Image image;  // linear RGBA, row 0 at the top
  FrameStats stats;
};

absl::Status ValidateRenderSettings(const RenderSettings& settings);

absl::StatusOr<RenderedFrame> RenderFrame(const Scene& scene, const Camera& camera,
                                          const RenderSettings& settings);

}  // namespace aperture
