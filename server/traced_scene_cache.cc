#include "traced_scene_cache.h"

#include <chrono>

namespace aperture {
namespace {

// The TracedScene and the Scene it refers to, freed together.
struct Holder {
  std::shared_ptr<const Scene> scene;
  std::unique_ptr<TracedScene> traced;
};

}  // namespace

absl::StatusOr<std::shared_ptr<const TracedScene>> TracedSceneCache::Get(
    const std::string& id, std::shared_ptr<const Scene> scene, double* built_ms,
    const StopRequested& stop) {
  if (built_ms != nullptr) *built_ms = 0;
  std::shared_ptr<Slot> slot;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    Entry& entry = entries_[id];
    if (!entry.slot) entry.slot = std::make_shared<Slot>();
    entry.last_use = ++clock_;
    slot = entry.slot;
    while (entries_.size() > capacity_) {
      auto oldest = entries_.begin();
      for (auto it = entries_.begin(); it != entries_.end(); ++it)
        if (it->second.last_use < oldest->second.last_use) oldest = it;
      entries_.erase(oldest);
    }
  }
  std::lock_guard<std::mutex> lock(slot->mutex);
  if (slot->traced) return slot->traced;
  const auto start = std::chrono::steady_clock::now();
  auto holder = std::make_shared<Holder>();
  holder->scene = std::move(scene);
  // A build stopped by the frame's deadline is not kept: the next frame builds again.
  auto traced = TracedScene::Build(*holder->scene, store_, stop, memory_budget_);
  if (!traced.ok()) return traced.status();
  holder->traced = std::move(*traced);
  slot->traced = std::shared_ptr<const TracedScene>(holder, holder->traced.get());
  if (built_ms != nullptr)
    *built_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return slot->traced;
}

size_t TracedSceneCache::size() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return entries_.size();
}

}  // namespace aperture
