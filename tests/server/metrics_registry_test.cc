// The Prometheus text exposition format of MetricsRegistry: HELP and TYPE per family, label
// values escaped, cumulative histogram buckets ending at +Inf with _sum and _count, values
// written exactly; and ServiceMetrics' refusal counting.
#include "metrics_registry.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <limits>

#include "service_metrics.h"

namespace aperture {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

TEST(MetricsRegistry, WritesTheTextExpositionFormat) {
  MetricsRegistry registry;
  MetricsRegistry::Counter& calls =
      registry.AddCounter("calls_total", "calls by method\nand code", {"method", "code"});
  MetricsRegistry::Histogram& latency =
      registry.AddHistogram("latency_seconds", "latency", {"stage"}, {0.1, 0.01, 1});
  registry.AddGauge("queue_depth", "queued", [] { return 3.0; });
  registry.AddCounterFunction("evictions_total", "evicted", [] { return 12345678901.0; });
  calls.Increment({"a/B", "OK"});
  calls.Increment({"a/B", "OK"}, 2);
  calls.Increment({"say \"hi\"\\\n", "UNAUTHENTICATED"});
  latency.Observe({"queue"}, 0.005);
  latency.Observe({"queue"}, 0.1);  // le is "less than or equal"
  latency.Observe({"queue"}, 7);

  const std::string text = registry.Text();
  EXPECT_THAT(text, HasSubstr("# HELP calls_total calls by method\\nand code\n"
                              "# TYPE calls_total counter\n"
                              "calls_total{method=\"a/B\",code=\"OK\"} 3\n"));
  EXPECT_THAT(text, HasSubstr("calls_total{method=\"say \\\"hi\\\"\\\\\\n\","
                              "code=\"UNAUTHENTICATED\"} 1\n"));
  EXPECT_THAT(text, HasSubstr("# TYPE latency_seconds histogram\n"
                              "latency_seconds_bucket{stage=\"queue\",le=\"0.01\"} 1\n"
                              "latency_seconds_bucket{stage=\"queue\",le=\"0.1\"} 2\n"
                              "latency_seconds_bucket{stage=\"queue\",le=\"1\"} 2\n"
                              "latency_seconds_bucket{stage=\"queue\",le=\"+Inf\"} 3\n"
                              "latency_seconds_sum{stage=\"queue\"} 7.105\n"
                              "latency_seconds_count{stage=\"queue\"} 3\n"));
  EXPECT_THAT(text, HasSubstr("# TYPE queue_depth gauge\nqueue_depth 3\n"));
  EXPECT_THAT(text, HasSubstr("# TYPE evictions_total counter\nevictions_total 12345678901\n"));
  // Families in the order they were added.
  EXPECT_LT(text.find("calls_total"), text.find("latency_seconds"));
  EXPECT_LT(text.find("latency_seconds"), text.find("queue_depth"));
}

TEST(MetricsRegistry, ValuesAreExactOrShortest) {
  EXPECT_EQ(MetricValueText(0), "0");
  EXPECT_EQ(MetricValueText(16606694), "16606694");
  EXPECT_EQ(MetricValueText(0.0333), "0.0333");
  EXPECT_EQ(MetricValueText(1.0 / 3), "0.3333333333333333");
  EXPECT_EQ(MetricValueText(std::numeric_limits<double>::infinity()), "+Inf");
  EXPECT_EQ(MetricValueText(std::numeric_limits<double>::quiet_NaN()), "NaN");
}

TEST(ServiceMetrics, CountsRefusalsFramesAndStages) {
  ServiceMetrics metrics;
  metrics.RpcAnswered("aperture.v1.Render/GetServerInfo", "UNAUTHENTICATED");
  metrics.RpcAnswered("aperture.v1.Render/RenderFrame", "OK");
  FrameAnswerMetrics frame;
  frame.mode = "raster";
  frame.status = "OK";
  frame.rendered = true;
  frame.raster_s = 0.04;
  frame.total_s = 0.5;
  frame.send_s = 0.25;
  frame.bytes = 1000;
  metrics.FrameAnswered(frame);
  metrics.FrameAnswered({.mode = "raytrace", .status = "RESOURCE_EXHAUSTED"});
  metrics.FrameSkipped("superseded");
  const std::string text = metrics.Text();
  EXPECT_THAT(text, HasSubstr("aperture_auth_refusals_total{method=\"aperture.v1.Render/"
                              "GetServerInfo\"} 1\n"));
  EXPECT_THAT(text, Not(HasSubstr("aperture_auth_refusals_total{method=\"aperture.v1.Render/"
                                  "RenderFrame\"}")));
  EXPECT_THAT(text, HasSubstr("aperture_frames_total{mode=\"raster\",status=\"OK\"} 1\n"));
  EXPECT_THAT(
      text, HasSubstr("aperture_frames_total{mode=\"raytrace\",status=\"RESOURCE_EXHAUSTED\"} 1"));
  EXPECT_THAT(text, HasSubstr("aperture_frames_skipped_total{reason=\"superseded\"} 1\n"));
  EXPECT_THAT(text, HasSubstr("aperture_frame_stage_seconds_count{stage=\"send\"} 1\n"));
  EXPECT_THAT(text, HasSubstr("aperture_frame_latency_seconds_sum{mode=\"raster\"} 0.75\n"));
  EXPECT_THAT(text, HasSubstr("aperture_frame_bytes_total{mode=\"raster\"} 1000\n"));
}

}  // namespace
}  // namespace aperture
