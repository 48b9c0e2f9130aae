#include "region_plan_request.h"

#include "frame_request.h"
#include "render/frame_regions.h"

namespace aperture {

absl::Status PlanRegionsForRequest(const Scene& scene, const v1::PlanRegionsRequest& request,
                                   uint64_t max_pixels, v1::PlanRegionsResponse* response) {
  v1::RenderFrameRequest frame;
  if (request.has_camera()) *frame.mutable_camera() = request.camera();
  *frame.mutable_options() = request.options();
  auto job = ParseFrameRequest(frame, max_pixels);
  if (!job.ok()) return job.status();
  auto regions =
      PlanRegions(scene, job->camera, job->settings, static_cast<int>(request.regions()));
  if (!regions.ok()) return regions.status();
  for (const FrameRegion& r : *regions) {
    v1::PlannedRegion& planned = *response->add_regions();
    planned.mutable_region()->set_x(static_cast<uint32_t>(r.rect.x0));
    planned.mutable_region()->set_y(static_cast<uint32_t>(r.rect.y0));
    planned.mutable_region()->set_width(static_cast<uint32_t>(r.rect.width()));
    planned.mutable_region()->set_height(static_cast<uint32_t>(r.rect.height()));
    planned.set_predicted_ms(r.predicted_us / 1000.0);
  }
  return absl::OkStatus();
}

}  // namespace aperture
