// Admission control: at most `concurrent` frames render at once; up to `max_queue` more wait for
// a turn, first come first served; past that a request is refused at once (RESOURCE_EXHAUSTED),
// never left to hang.
#pragma once

#include <condition_variable>
#include <cstdint>
#include <functional>
#include <mutex>
#include <set>

#include "absl/status/statusor.h"

namespace aperture {

class AdmissionControl {
 public:
  AdmissionControl(int concurrent, int max_queue)
      : concurrent_(concurrent), max_queue_(max_queue) {}

  // A turn to render; the turn ends when the ticket is destroyed.
  class Ticket {
   public:
    explicit Ticket(AdmissionControl* owner) : owner_(owner) {}
    Ticket(Ticket&& other) noexcept : owner_(other.owner_) { other.owner_ = nullptr; }
    Ticket& operator=(Ticket&&) = delete;
    ~Ticket();

   private:
    AdmissionControl* owner_;
  };

  // Waits for a turn while `stop` is false (polled every few milliseconds). RESOURCE_EXHAUSTED
  // when the queue is full, CANCELLED when `stop` became true first.
  absl::StatusOr<Ticket> Enter(const std::function<bool()>& stop);

  int running() const;
  int queued() const;
  uint64_t rejected() const;

 private:
  void Leave();

  const int concurrent_, max_queue_;
  mutable std::mutex mutex_;
  std::condition_variable turn_;
  int running_ = 0;
  uint64_t next_number_ = 0;
  std::set<uint64_t> waiting_;  // numbers of the queued requests, in arrival order
  uint64_t rejected_ = 0;
};

}  // namespace aperture
