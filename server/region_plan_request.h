// A PlanRegions request made into the engine's region plan: the same validation as a
// frame request (camera, options, size limit), then engine/render/frame_regions.
#pragma once

#include <cstdint>

#include "absl/status/status.h"
#include "aperture/v1/render_service.pb.h"
#include "scene/scene.h"

namespace aperture {

absl::Status PlanRegionsForRequest(const Scene& scene, const v1::PlanRegionsRequest& request,
                                   uint64_t max_pixels, v1::PlanRegionsResponse* response);

}  // namespace aperture
