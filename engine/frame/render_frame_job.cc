#include "frame/render_frame_job.h"

#include "render/frame_renderer.h"

namespace aperture {

absl::StatusOr<RenderedFrame> RenderFrameJob(const Scene& scene, const FrameJob& job,
                                             const TracedSceneSource& traced,
                                             const StopRequested& stop, TraceStats* trace_stats) {
  if (!job.mode.raytrace) return RenderFrame(scene, job.camera, job.settings, stop);
  absl::StatusOr<std::shared_ptr<const TracedScene>> rays;
  if (traced) {
    rays = traced();
  } else {
    auto built = TracedScene::Build(scene, nullptr, stop);
    if (built.ok())
      rays = std::shared_ptr<const TracedScene>(*std::move(built));
    else
      rays = built.status();
  }
  if (!rays.ok()) return rays.status();
  return (*rays)->Render(job.camera, job.settings, job.mode.trace, trace_stats, stop);
}

const char* FrameJobModeName(const FrameJob& job) {
  return job.mode.raytrace ? "raytrace" : "raster";
}

ExrMetadata FrameJobMetadata(const std::string& scene_name, const FrameJob& job,
                             const RenderedFrame& frame) {
  return FrameMetadata(scene_name, job.camera, frame, job.settings.width, job.settings.height,
                       FrameJobModeName(job));
}

}  // namespace aperture
