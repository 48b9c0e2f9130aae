#include "metrics_interceptor.h"

#include <chrono>
#include <map>
#include <mutex>
#include <optional>
#include <string>

#include "absl/status/status.h"
#include "absl/strings/match.h"
#include "absl/strings/string_view.h"
#include "aperture/v1/render_service.pb.h"

namespace aperture {
namespace {

using grpc::experimental::InterceptionHookPoints;
using Clock = std::chrono::steady_clock;

// A stream holds at most this many requests' modes waiting for their answers (it answers every
// request it reads, in order, and reads no further while 64 answers wait: live_stream.h).
constexpr size_t kMaxPendingModes = 256;

const char* ModeName(v1::RenderMode mode) {
  return mode == v1::RENDER_MODE_RAYTRACE ? "raytrace" : "raster";
}

std::string CodeName(int code) {
  return absl::StatusCodeToString(static_cast<absl::StatusCode>(code));
}

class MetricsInterceptor final : public grpc::experimental::Interceptor {
 public:
  MetricsInterceptor(ServiceMetrics& metrics, std::string method, bool frames, bool unary)
      : metrics_(metrics), method_(std::move(method)), frames_(frames), unary_(unary) {}

  void Intercept(grpc::experimental::InterceptorBatchMethods* methods) override {
    if (frames_) ObserveFrames(methods);
    if (methods->QueryInterceptionHookPoint(InterceptionHookPoints::PRE_SEND_STATUS)) {
      const grpc::Status status = methods->GetSendStatus();
      const std::string code = CodeName(status.error_code());
      metrics_.RpcAnswered(method_, code);
      // A RenderFrame that fails sends no message: its frame is counted with its status here.
      if (frames_ && unary_ && !status.ok()) {
        FrameAnswerMetrics frame;
        frame.mode = TakeMode(0, /*any=*/true);
        frame.status = code;
        metrics_.FrameAnswered(frame);
      }
    }
    methods->Proceed();
  }

 private:
  void ObserveFrames(grpc::experimental::InterceptorBatchMethods* methods) {
    // Two threads of a stream (its reader and its writer) may be here at once.
    std::lock_guard lock(mutex_);
    if (methods->QueryInterceptionHookPoint(InterceptionHookPoints::POST_RECV_MESSAGE)) {
      if (const auto* request =
              static_cast<const v1::RenderFrameRequest*>(methods->GetRecvMessage())) {
        if (modes_.size() >= kMaxPendingModes) modes_.erase(modes_.begin());
        modes_[request->frame_index()] = ModeName(request->options().mode());
      }
    }
    if (methods->QueryInterceptionHookPoint(InterceptionHookPoints::PRE_SEND_MESSAGE)) {
      if (const auto* response =
              static_cast<const v1::RenderFrameResponse*>(methods->GetSendMessage())) {
        pending_ = Summary(*response);
        send_start_ = Clock::now();
      }
    }
    if (methods->QueryInterceptionHookPoint(InterceptionHookPoints::POST_SEND_MESSAGE) &&
        pending_) {
      PendingAnswer answer = *std::move(pending_);
      pending_.reset();
      if (!answer.skipped_reason.empty()) {
        metrics_.FrameSkipped(answer.skipped_reason);
        return;
      }
      answer.frame.send_s = std::chrono::duration<double>(Clock::now() - send_start_).count();
      metrics_.FrameAnswered(answer.frame);
    }
  }

  // An answer on its way to the transport: a frame, or a request skipped for a reason.
  struct PendingAnswer {
    std::string skipped_reason;  // "superseded", "late"; empty for a frame
    FrameAnswerMetrics frame;
  };

  PendingAnswer Summary(const v1::RenderFrameResponse& response) {
    PendingAnswer answer;
    const std::string mode = TakeMode(response.frame_index(), unary_);
    if (response.outcome() == v1::FRAME_OUTCOME_SKIPPED_SUPERSEDED ||
        response.outcome() == v1::FRAME_OUTCOME_SKIPPED_LATE) {
      answer.skipped_reason =
          response.outcome() == v1::FRAME_OUTCOME_SKIPPED_LATE ? "late" : "superseded";
      return answer;
    }
    FrameAnswerMetrics& frame = answer.frame;
    frame.mode = mode;
    frame.status = CodeName(response.status_code());
    frame.rendered = response.status_code() == 0;
    const v1::FrameTimings& t = response.timings();
    frame.update_s = t.update_ms() / 1000;
    frame.queue_s = t.queue_ms() / 1000;
    frame.setup_s = t.setup_ms() / 1000;
    frame.raster_s = t.raster_ms() / 1000;
    frame.encode_s = t.encode_ms() / 1000;
    frame.total_s = t.total_ms() / 1000;
    frame.bytes = response.exr().size();
    return answer;
  }

  // The mode of the request `frame_index` (a unary call's one request: `any`), forgotten now.
  std::string TakeMode(uint64_t frame_index, bool any) {
    auto found = any ? modes_.begin() : modes_.find(frame_index);
    if (found == modes_.end()) return "raster";
    std::string mode = found->second;
    modes_.erase(found);
    return mode;
  }

  ServiceMetrics& metrics_;
  const std::string method_;
  const bool frames_;  // RenderFrame or RenderStream
  const bool unary_;
  std::mutex mutex_;
  std::map<uint64_t, std::string> modes_;  // requests read, by frame index, not yet answered
  std::optional<PendingAnswer> pending_;   // the answer being sent
  Clock::time_point send_start_;
};

class MetricsInterceptorFactoryImpl final
    : public grpc::experimental::ServerInterceptorFactoryInterface {
 public:
  explicit MetricsInterceptorFactoryImpl(ServiceMetrics& metrics) : metrics_(metrics) {}

  grpc::experimental::Interceptor* CreateServerInterceptor(
      grpc::experimental::ServerRpcInfo* info) override {
    absl::string_view method = info->method() != nullptr ? info->method() : "";
    if (absl::StartsWith(method, "/")) method.remove_prefix(1);
    const bool frames =
        method == "aperture.v1.Render/RenderFrame" || method == "aperture.v1.Render/RenderStream";
    return new MetricsInterceptor(metrics_, std::string(method), frames,
                                  info->type() == grpc::experimental::ServerRpcInfo::Type::UNARY);
  }

 private:
  ServiceMetrics& metrics_;
};

}  // namespace

std::unique_ptr<grpc::experimental::ServerInterceptorFactoryInterface> MetricsInterceptorFactory(
    ServiceMetrics& metrics) {
  return std::make_unique<MetricsInterceptorFactoryImpl>(metrics);
}

}  // namespace aperture
