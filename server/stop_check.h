// Whether a request's frame should stop: true once the client cancels, its deadline passes,
// or the server shuts down past its grace period (gRPC then cancels the call). Polled by render
// workers between tasks, so the call's state is looked at no more than once a millisecond.
#pragma once

#include <grpcpp/server_context.h>

#include <atomic>
#include <chrono>

namespace aperture {

class StopCheck {
 public:
  explicit StopCheck(grpc::ServerContext* context) : context_(context) {}

  bool operator()() {
    if (stopped_.load(std::memory_order_relaxed)) return true;
    const int64_t now = std::chrono::steady_clock::now().time_since_epoch().count();
    int64_t next = next_check_.load(std::memory_order_relaxed);
    if (now < next || !next_check_.compare_exchange_strong(next, now + kInterval)) return false;
    if (context_->IsCancelled() || std::chrono::system_clock::now() > context_->deadline())
      stopped_.store(true, std::memory_order_relaxed);
    return stopped_.load(std::memory_order_relaxed);
  }

 private:
  static constexpr int64_t kInterval =
      std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::milliseconds(1))
          .count();
  grpc::ServerContext* context_;
  std::atomic<bool> stopped_{false};
  std::atomic<int64_t> next_check_{0};
};

}  // namespace aperture
