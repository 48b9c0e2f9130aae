// The split of a frame over K renderers: the scene projected as RenderFrame would
// project it, then cut into K bands of equal predicted cost (cost/region_planner.h).
#pragma once

#include <vector>

#include "absl/status/statusor.h"
#include "cost/region_planner.h"
#include "render/frame_renderer.h"

namespace aperture {

inline constexpr int kMaxFrameRegions = 256;

// InvalidArgument when `k` is outside 1..min(kMaxFrameRegions, height) or the settings are bad.
absl::StatusOr<std::vector<FrameRegion>> PlanRegions(const Scene& scene, const Camera& camera,
                                                     const RenderSettings& settings, int k);

}  // namespace aperture
