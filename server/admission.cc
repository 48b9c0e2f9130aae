#include "admission.h"

#include <chrono>

#include "absl/strings/str_cat.h"
#include "refusal_log.h"

namespace aperture {

AdmissionControl::Ticket::~Ticket() {
  if (owner_) owner_->Leave();
}

absl::StatusOr<AdmissionControl::Ticket> AdmissionControl::Enter(
    const std::function<bool()>& stop) {
  std::unique_lock lock(mutex_);
  if (running_ < concurrent_ && waiting_.empty()) {
    ++running_;
    return Ticket(this);
  }
  if (static_cast<int>(waiting_.size()) >= max_queue_) {
    ++rejected_;
    return MarkRefusal(absl::ResourceExhaustedError(absl::StrCat(
                           "server busy: ", running_, " frames rendering and ", waiting_.size(),
                           " waiting (--max-queue ", max_queue_, "); retry later")),
                       kQueueFullRefusal);
  }
  const uint64_t number = next_number_++;
  waiting_.insert(number);
  // The oldest waiter takes the next free turn.
  while (running_ >= concurrent_ || *waiting_.begin() != number) {
    if (stop()) {
      waiting_.erase(number);
      turn_.notify_all();  // the next waiter may now be the oldest
      return absl::CancelledError("request cancelled while waiting in the queue");
    }
    turn_.wait_for(lock, std::chrono::milliseconds(5));
  }
  waiting_.erase(number);
  ++running_;
  turn_.notify_all();
  return Ticket(this);
}

void AdmissionControl::Leave() {
  {
    std::lock_guard lock(mutex_);
    --running_;
  }
  turn_.notify_all();
}

int AdmissionControl::running() const {
  std::lock_guard lock(mutex_);
  return running_;
}

int AdmissionControl::queued() const {
  std::lock_guard lock(mutex_);
  return static_cast<int>(waiting_.size());
}

uint64_t AdmissionControl::rejected() const {
  std::lock_guard lock(mutex_);
  return rejected_;
}

}  // namespace aperture
