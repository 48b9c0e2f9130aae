#include "render/renderer.h"

#include <cmath>

#include "absl/strings/str_cat.h"

namespace aperture {

double FrameStats::BalanceEfficiency() const {
  double busy_us = 0;
  for (const TaskTiming& t : tasks) busy_us += t.measured_us;
  return raster_ms > 0 ? busy_us / (1000.0 * raster_ms * concurrency) : 0;
}

absl::Status ValidateRenderSettings(const RenderSettings& s) {
  if (s.width <= 0 || s.height <= 0 || s.width > kMaxImageSide || s.height > kMaxImageSide)
    return absl::InvalidArgumentError(absl::StrCat("image size ", s.width, "x", s.height,
                                                   " is outside 1..", kMaxImageSide, " per side"));
  if (!std::isfinite(s.shading.texture_aperture) || s.shading.texture_aperture <= 0 ||
      s.shading.texture_aperture > 16)
    return absl::InvalidArgumentError("texture aperture must be in (0, 16] pixels");
  if (s.threads < 0) return absl::InvalidArgumentError("threads must be >= 0");
  const PixelRect& r = s.region;
  if (r.pixels() != 0 && (r.x0 < 0 || r.y0 < 0 || r.x1 > s.width || r.y1 > s.height ||
                          r.width() <= 0 || r.height() <= 0))
    return absl::InvalidArgumentError(absl::StrCat("region [", r.x0, ", ", r.x1, ") x [", r.y0,
                                                   ", ", r.y1, ") is not inside the ", s.width, "x",
                                                   s.height, " frame"));
  if (s.warnock.leaf_size < 1) return absl::InvalidArgumentError("Warnock leaf size must be >= 1");
  if (s.warnock.crowded_leaf_size < 1)
    return absl::InvalidArgumentError("Warnock crowded leaf size must be >= 1");
  if (s.scheduling.uniform_tile < 8 || s.scheduling.tasks_per_thread < 1)
    return absl::InvalidArgumentError("uniform tiles must be >= 8 pixels, tasks per thread >= 1");
  if (s.scheduling.plan_workers < 0 || s.scheduling.plan_workers > kMaxPlanWorkers)
    return absl::InvalidArgumentError(
        absl::StrCat("planned workers must be in 0..", kMaxPlanWorkers, " (0: the threads used)"));
  return absl::OkStatus();
}

}  // namespace aperture
