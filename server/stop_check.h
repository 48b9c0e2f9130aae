// Whether a request's frame should stop: true once the client cancels, its deadline passes (the
// call's, or a stream frame's own `deadline_ms`), or the server shuts down past its grace period
// (gRPC then cancels the call). Polled by render workers between tasks, so the call's state is
// looked at no more than once a millisecond.
#pragma once

#include <grpcpp/server_context.h>

#include <atomic>
#include <chrono>

#include "absl/status/status.h"
#include "absl/strings/str_cat.h"

namespace aperture {

class StopCheck {
 public:
  explicit StopCheck(grpc::ServerContext* context,
                     std::chrono::steady_clock::time_point frame_deadline =
                         std::chrono::steady_clock::time_point::max())
      : context_(context), frame_deadline_(frame_deadline) {}

  bool operator()() {
    if (stopped_.load(std::memory_order_relaxed)) return true;
    const auto steady_now = std::chrono::steady_clock::now();
    const int64_t now = steady_now.time_since_epoch().count();
    int64_t next = next_check_.load(std::memory_order_relaxed);
    if (now < next || !next_check_.compare_exchange_strong(next, now + kInterval)) return false;
    if (context_->IsCancelled() || std::chrono::system_clock::now() > context_->deadline() ||
        steady_now > frame_deadline_)
      stopped_.store(true, std::memory_order_relaxed);
    return stopped_.load(std::memory_order_relaxed);
  }

  // Whether the frame's own deadline (not the call's) is what stopped it.
  bool FrameDeadlinePassed() const { return std::chrono::steady_clock::now() > frame_deadline_; }
  // Whether a deadline (the frame's or the call's), not a cancellation, is what stopped it.
  // gRPC cancels a call when its deadline timer fires, which can be a little before this
  // process's clock reads the deadline: a cancellation within kDeadlineSlack of it counts as
  // the deadline.
  bool DeadlinePassed() const {
    return FrameDeadlinePassed() ||
           std::chrono::system_clock::now() + kDeadlineSlack >= context_->deadline();
  }

 private:
  static constexpr std::chrono::milliseconds kDeadlineSlack{10};
  static constexpr int64_t kInterval =
      std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::milliseconds(1))
          .count();
  grpc::ServerContext* context_;
  const std::chrono::steady_clock::time_point frame_deadline_;
  std::atomic<bool> stopped_{false};
  std::atomic<int64_t> next_check_{0};
};

// `status` as the client should read it: a CANCELLED that a passed deadline caused becomes
// DEADLINE_EXCEEDED saying which deadline passed and `during` what ("while its scene update was
// applied"), followed by the engine's account of how far it got. Anything else is returned as is.
inline absl::Status WhyStopped(const absl::Status& status, const StopCheck& stop,
                               const char* during) {
  if (!absl::IsCancelled(status) || !stop.DeadlinePassed()) return status;
  return absl::DeadlineExceededError(
      absl::StrCat(stop.FrameDeadlinePassed() ? "the frame's deadline_ms" : "the call's deadline",
                   " passed ", during, "; nothing of it applies (", status.message(), ")"));
}

}  // namespace aperture
