// What aperture-server tells a monitoring system (--metrics-listen; docs/SERVICE.md, "Metrics"):
// every RPC by method and status code, authentication refusals, frames by mode and status,
// skipped frames by reason, the frame latency and each stage's time (update, queue, setup,
// raster, encode, send) as histograms, bytes of frames sent, and, read at each scrape, the
// admission queue, the texture store and the loaded scenes. Fed by the metrics interceptor
// (metrics_interceptor.h), which sees every call's messages and status, so the handlers carry no
// metrics code.
#pragma once

#include <string>

#include "admission.h"
#include "metrics_registry.h"
#include "scene_store.h"
#include "texture_store.h"

namespace aperture {

// One frame's answer as the interceptor saw it.
struct FrameAnswerMetrics {
  std::string mode;       // "raster" or "raytrace"
  std::string status;     // the gRPC status code's name: "OK", "RESOURCE_EXHAUSTED", ...
  bool rendered = false;  // rendered and encoded: its stage times below are set
  double update_s = 0, queue_s = 0, setup_s = 0, raster_s = 0, encode_s = 0;
  double total_s = 0;  // received to encoded (the response's total_ms)
  double send_s = 0;   // the answer handed to gRPC's transport
  uint64_t bytes = 0;  // the EXR's
};

class ServiceMetrics {
 public:
  ServiceMetrics();
  ServiceMetrics(const ServiceMetrics&) = delete;
  ServiceMetrics& operator=(const ServiceMetrics&) = delete;

  // The gauges and counters the server keeps itself, read at each scrape; they must outlive
  // this object's last Text().
  void Watch(const AdmissionControl& admission, const TextureStore& textures,
             const SceneStore& scenes, uint64_t store_budget_bytes);

  // `method` as gRPC names it without the leading slash ("aperture.v1.Render/RenderFrame").
  void RpcAnswered(const std::string& method, const std::string& code);
  void FrameAnswered(const FrameAnswerMetrics& frame);
  void FrameSkipped(const std::string& reason);  // "superseded" or "late"

  std::string Text() const { return registry_.Text(); }

 private:
  MetricsRegistry registry_;
  MetricsRegistry::Counter& rpcs_;
  MetricsRegistry::Counter& auth_refusals_;
  MetricsRegistry::Counter& frames_;
  MetricsRegistry::Counter& skipped_;
  MetricsRegistry::Counter& frame_bytes_;
  MetricsRegistry::Histogram& latency_;
  MetricsRegistry::Histogram& stages_;
};

}  // namespace aperture
