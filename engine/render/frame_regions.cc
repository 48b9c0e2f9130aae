#include "render/frame_regions.h"

#include <algorithm>

#include "absl/strings/str_cat.h"

namespace aperture {

absl::StatusOr<std::vector<FrameRegion>> PlanRegions(const Scene& scene, const Camera& camera,
                                                     const RenderSettings& settings, int k) {
  if (auto s = ValidateRenderSettings(settings); !s.ok()) return s;
  const int most = std::min(kMaxFrameRegions, settings.height);
  if (k < 1 || k > most)
    return absl::InvalidArgumentError(absl::StrCat("regions: ", k, " is not in 1..", most,
                                                   " (at most one per row, and ", kMaxFrameRegions,
                                                   ")"));
  const AaFilterShape shape = ShapeOf(settings.aa);
  const FrameGeometry geometry =
      ProjectScene(scene, camera, settings.width, settings.height, shape.margin + 1.0);
  return PlanFrameRegions(geometry, shape, k, settings.scheduling.model);
}

}  // namespace aperture
