#include "idle_watchdog.h"

#include <algorithm>

namespace aperture {

IdleWatchdog::IdleWatchdog(std::chrono::milliseconds idle_limit)
    : idle_limit_(idle_limit), thread_([this] { Run(); }) {}

IdleWatchdog::~IdleWatchdog() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_all();
  thread_.join();
}

std::unique_ptr<IdleWatchdog::Watch> IdleWatchdog::Start(grpc::ServerContext* context) {
  std::lock_guard<std::mutex> lock(mutex_);
  entries_.push_back({context, std::chrono::steady_clock::now()});
  return std::unique_ptr<Watch>(new Watch(this, std::prev(entries_.end())));
}

IdleWatchdog::Watch::~Watch() {
  std::lock_guard<std::mutex> lock(dog_->mutex_);
  dog_->entries_.erase(entry_);
}

void IdleWatchdog::Watch::Touch() {
  std::lock_guard<std::mutex> lock(dog_->mutex_);
  entry_->last = std::chrono::steady_clock::now();
}

bool IdleWatchdog::Watch::Expired() const {
  std::lock_guard<std::mutex> lock(dog_->mutex_);
  return entry_->expired;
}

void IdleWatchdog::Run() {
  // Four looks per idle period: a call is cancelled between 1 and 1.25 periods after its last
  // message.
  const auto period = std::max(std::chrono::milliseconds(10), idle_limit_ / 4);
  std::unique_lock<std::mutex> lock(mutex_);
  while (!stopping_) {
    wake_.wait_for(lock, period, [this] { return stopping_; });
    const auto now = std::chrono::steady_clock::now();
    for (Entry& entry : entries_)
      if (!entry.expired && now - entry.last > idle_limit_) {
        entry.expired = true;
        entry.context->TryCancel();
      }
  }
}

}  // namespace aperture
