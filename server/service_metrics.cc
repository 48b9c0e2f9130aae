#include "service_metrics.h"

namespace aperture {
namespace {

// Seconds, from a millisecond stage to a frame that missed its 30 Hz slot several times over.
const std::vector<double> kSecondsBuckets = {0.001, 0.002, 0.005, 0.01, 0.02, 0.0333, 0.05, 0.075,
                                             0.1,   0.15,  0.25,  0.5,  1,    2.5,    5,    10};

}  // namespace

ServiceMetrics::ServiceMetrics()
    : rpcs_(registry_.AddCounter("aperture_rpcs_total",
                                 "RPCs answered, by gRPC method and status code",
                                 {"method", "code"})),
      auth_refusals_(registry_.AddCounter(
          "aperture_auth_refusals_total",
          "calls refused UNAUTHENTICATED (no or no accepted bearer token), by method", {"method"})),
      frames_(registry_.AddCounter(
          "aperture_frames_total",
          "frames answered by RenderFrame and RenderStream (skipped ones apart), by render mode "
          "and gRPC status code",
          {"mode", "status"})),
      skipped_(registry_.AddCounter(
          "aperture_frames_skipped_total",
          "stream requests answered without a frame: superseded by a newer state or too late for "
          "their deadline",
          {"reason"})),
      frame_bytes_(registry_.AddCounter("aperture_frame_bytes_total",
                                        "EXR bytes of the frames rendered, by render mode",
                                        {"mode"})),
      latency_(registry_.AddHistogram(
          "aperture_frame_latency_seconds",
          "a rendered frame's time from its request's arrival to its answer handed to gRPC's "
          "transport",
          {"mode"}, kSecondsBuckets)),
      stages_(registry_.AddHistogram(
          "aperture_frame_stage_seconds",
          "a rendered frame's time in each stage: update (its scene update), queue (admission), "
          "setup (projection; raytrace: corner rays), raster (pixels), encode (EXR), send (to "
          "gRPC's transport)",
          {"stage"}, kSecondsBuckets)) {}

void ServiceMetrics::Watch(const AdmissionControl& admission, const TextureStore& textures,
                           const SceneStore& scenes, uint64_t store_budget_bytes) {
  registry_.AddGauge("aperture_admission_queue_depth", "frames waiting for a turn to render",
                     [&admission] { return static_cast<double>(admission.queued()); });
  registry_.AddGauge("aperture_frames_in_flight", "frames rendering now",
                     [&admission] { return static_cast<double>(admission.running()); });
  registry_.AddCounterFunction("aperture_admission_rejected_total",
                               "frames refused at once because the queue was full",
                               [&admission] { return static_cast<double>(admission.rejected()); });
  registry_.AddGauge("aperture_store_bytes", "bytes the texture store holds",
                     [&textures] { return static_cast<double>(textures.bytes()); });
  registry_.AddGauge("aperture_store_budget_bytes", "the texture store's budget (--max-store-mb)",
                     [store_budget_bytes] { return static_cast<double>(store_budget_bytes); });
  registry_.AddCounterFunction(
      "aperture_store_evictions_total",
      "texture store entries evicted (least recently used) to stay within the budget",
      [&textures] { return static_cast<double>(textures.evicted()); });
  registry_.AddGauge("aperture_scenes_loaded", "scenes loaded",
                     [&scenes] { return static_cast<double>(scenes.size()); });
  registry_.AddGauge("aperture_scene_bytes", "estimated bytes of the loaded scenes",
                     [&scenes] { return static_cast<double>(scenes.bytes()); });
  registry_.AddGauge("aperture_scene_budget_bytes", "the loaded scenes' budget (--max-scenes-mb)",
                     [&scenes] { return static_cast<double>(scenes.budget()); });
  registry_.AddCounterFunction("aperture_scene_evictions_total",
                               "loaded scenes dropped (least recently used)",
                               [&scenes] { return static_cast<double>(scenes.evicted()); });
}

void ServiceMetrics::RpcAnswered(const std::string& method, const std::string& code) {
  rpcs_.Increment({method, code});
  if (code == "UNAUTHENTICATED") auth_refusals_.Increment({method});
}

void ServiceMetrics::FrameAnswered(const FrameAnswerMetrics& frame) {
  frames_.Increment({frame.mode, frame.status});
  if (!frame.rendered) return;
  frame_bytes_.Increment({frame.mode}, static_cast<double>(frame.bytes));
  latency_.Observe({frame.mode}, frame.total_s + frame.send_s);
  stages_.Observe({"update"}, frame.update_s);
  stages_.Observe({"queue"}, frame.queue_s);
  stages_.Observe({"setup"}, frame.setup_s);
  stages_.Observe({"raster"}, frame.raster_s);
  stages_.Observe({"encode"}, frame.encode_s);
  stages_.Observe({"send"}, frame.send_s);
}

void ServiceMetrics::FrameSkipped(const std::string& reason) { skipped_.Increment({reason}); }

}  // namespace aperture
