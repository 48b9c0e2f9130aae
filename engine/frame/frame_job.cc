#include "frame/frame_job.h"

#include <cmath>

#include "absl/strings/str_cat.h"
#include "frame/camera_proto.h"
#include "frame/exr_options_proto.h"

namespace aperture {

absl::StatusOr<FrameJob> FrameJobFromRequest(const v1::RenderFrameRequest& request,
                                             const FrameJobOptions& local) {
  FrameJob job;
  if (!request.has_camera()) return absl::InvalidArgumentError("camera is missing");
  auto camera = CameraFromProto(request.camera());
  if (!camera.ok()) return camera.status();  // its messages name the camera field
  job.camera = *camera;

  auto settings = RenderSettingsFromProto(request.options());
  if (!settings.ok()) return settings.status();
  job.settings = *settings;
  auto exr = ExrOptionsFromProto(request.options());
  if (!exr.ok()) return exr.status();
  job.exr = *exr;
  auto mode = ModeOptionsFromProto(request.options());
  if (!mode.ok()) return mode.status();
  job.mode = *mode;
  if (!std::isfinite(request.scene_time_s()))
    return absl::InvalidArgumentError(
        absl::StrCat("scene_time_s is ", request.scene_time_s(), "; must be finite"));
  job.settings.scene_time_s = request.scene_time_s();

  if (request.has_region()) {
    const v1::PixelRegion& r = request.region();
    const uint64_t x1 = uint64_t{r.x()} + r.width(), y1 = uint64_t{r.y()} + r.height();
    if (r.width() == 0 || r.height() == 0 || x1 > request.options().width() ||
        y1 > request.options().height())
      return absl::InvalidArgumentError(
          absl::StrCat("region: ", r.width(), "x", r.height(), " at (", r.x(), ", ", r.y(),
                       ") is empty or not inside the ", request.options().width(), "x",
                       request.options().height(), " frame"));
    job.settings.region = {static_cast<int>(r.x()), static_cast<int>(r.y()), static_cast<int>(x1),
                           static_cast<int>(y1)};
  }

  job.settings.threads = local.threads;
  job.settings.max_frame_bytes = local.max_frame_bytes;
  job.settings.warnock = local.warnock;
  job.settings.scheduling.mode = local.scheduling;
  job.settings.scheduling.uniform_tile = local.uniform_tile;
  if (auto s = ValidateRenderSettings(job.settings); !s.ok()) return s;
  if (local.zip_level < 1 || local.zip_level > 9)
    return absl::InvalidArgumentError(
        absl::StrCat("zip_level ", local.zip_level, " is outside 1..9"));
  job.exr.zip_level = local.zip_level;
  job.exr.threads = local.threads;  // encoding follows rendering: the cores are free again
  if (local.exact_steps < 0)
    return absl::InvalidArgumentError(
        absl::StrCat("exact_steps ", local.exact_steps, " is negative (0: fragments only)"));
  job.mode.trace.fragments.exact_steps = local.exact_steps;
  return job;
}

}  // namespace aperture
