#include <atomic>
#include <chrono>
#include <cstdio>
#include <map>
#include <mutex>
#include <thread>
#include <vector>

#include "absl/flags/flag.h"
#include "absl/status/status.h"
#include "absl/strings/str_cat.h"
#include "channel.h"
#include "client_flags.h"
#include "commands.h"
#include "exit_status.h"
#include "latency_stats.h"
#include "report_json.h"
#include "request_flags.h"
#include "scene_upload.h"

namespace aperture {

int RunLoad() {
  using Clock = std::chrono::steady_clock;
  auto channel = ConnectChannel(absl::GetFlag(FLAGS_server));
  if (!channel.ok()) return Fail("load", channel.status());
  auto stub = v1::Render::NewStub(*channel);
  auto scene = LoadSceneOnServer(*stub, absl::GetFlag(FLAGS_scene));
  if (!scene.ok()) return Fail("load", scene.status());
  auto request = FrameRequestFromFlags(*scene);
  if (!request.ok()) return Fail("load", request.status());
  const int concurrency = absl::GetFlag(FLAGS_concurrency);
  const int total = absl::GetFlag(FLAGS_requests);
  const auto start = Clock::now();
  const auto end =
      start + std::chrono::milliseconds(static_cast<int64_t>(absl::GetFlag(FLAGS_duration) * 1000));
  std::atomic<int> issued{0};
  std::mutex mutex;
  std::vector<double> ok_latencies;
  std::map<std::string, int> errors;

  std::vector<std::thread> workers;
  for (int w = 0; w < concurrency; ++w) {
    workers.emplace_back([&] {
      std::vector<double> latencies;
      std::map<std::string, int> codes;
      while (total > 0 ? issued++ < total : Clock::now() < end) {
        grpc::ClientContext context;
        context.set_deadline(DeadlineIn(absl::GetFlag(FLAGS_deadline_s)));
        v1::RenderFrameResponse response;
        const auto sent = Clock::now();
        const grpc::Status status = stub->RenderFrame(&context, *request, &response);
        if (status.ok())
          latencies.push_back(
              std::chrono::duration<double, std::milli>(Clock::now() - sent).count());
        else
          ++codes[absl::StatusCodeToString(static_cast<absl::StatusCode>(status.error_code()))];
      }
      std::lock_guard lock(mutex);
      ok_latencies.insert(ok_latencies.end(), latencies.begin(), latencies.end());
      for (const auto& [code, n] : codes) errors[code] += n;
    });
  }
  for (std::thread& t : workers) t.join();
  const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
  const LatencySummary s = Summarize(ok_latencies);
  int failed = 0;
  for (const auto& [code, n] : errors) failed += n;
  const double throughput = static_cast<double>(s.count) / seconds;
  if (absl::GetFlag(FLAGS_json)) {
    v1::LoadReport report;
    report.set_concurrency(static_cast<uint32_t>(concurrency));
    report.set_seconds(Rounded(seconds));
    report.set_ok(static_cast<uint32_t>(s.count));
    report.set_failed(static_cast<uint32_t>(failed));
    report.set_frames_per_s(Rounded(throughput));
    *report.mutable_latency_ms() = LatencyReport(s);
    for (const auto& [code, n] : errors) (*report.mutable_errors())[code] = n;
    std::printf("%s\n", ReportJson(report).c_str());
  } else {
    std::printf("%zu frames ok, %d failed in %.2f s at concurrency %d: %.2f frames/s\n", s.count,
                failed, seconds, concurrency, throughput);
    std::printf("latency ms: p50 %.2f  p90 %.2f  p99 %.2f  max %.2f  mean %.2f\n", s.p50, s.p90,
                s.p99, s.max, s.mean);
    for (const auto& [code, n] : errors) std::printf("errors %s: %d\n", code.c_str(), n);
  }
  return failed == 0 ? 0 : 1;  // a load run with failed requests is a failure (scripts, CI)
}

}  // namespace aperture
