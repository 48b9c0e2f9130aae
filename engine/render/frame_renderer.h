// The raster renderer, the frame pipeline: project the scene, subdivide the screen Warnock-style,
// and render the leaf windows on oneTBB workers with exact analytic edge anti-aliasing (seed 002,
// eq. 2). Its settings, result and stop test are render/renderer.h's, shared with the ray tracer.
#pragma once

#include "absl/status/statusor.h"
#include "render/renderer.h"
#include "scene/camera.h"
#include "scene/scene.h"

namespace aperture {

absl::StatusOr<RenderedFrame> RenderFrame(const Scene& scene, const Camera& camera,
                                          const RenderSettings& settings,
                                          const StopRequested& stop = {});

}  // namespace aperture
