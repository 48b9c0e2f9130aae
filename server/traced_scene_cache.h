// Seed 003's ray-tracing state (Embree BVH, summed-area tables) of the scenes frames ask to
// raytrace, built on a scene's first raytraced frame and kept for the next ones; with a shared
// store the tables live there, built once per machine and mapped by every server. Bounded: past
// `capacity` scenes the one used longest ago is dropped (frames rendering it keep it alive).
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <string>

#include "absl/status/statusor.h"
#include "render/trace_renderer.h"
#include "scene/scene.h"

namespace aperture {

class TracedSceneCache {
 public:
  // `store`: the machine's shared store, where the summed-area tables are kept (null: in memory).
  // Without a store, a scene's tables are built in memory, refused past `memory_budget` bytes
  // (TracedScene::Build).
  TracedSceneCache(size_t capacity, std::shared_ptr<const SharedStore> store,
                   uint64_t memory_budget = 0)
      : capacity_(capacity), store_(std::move(store)), memory_budget_(memory_budget) {}

  // The state of scene `id`, built from `scene` once even when frames ask at the same time;
  // `*built_ms` (optional) is the time spent building it in this call (0 when it was cached).
  absl::StatusOr<std::shared_ptr<const TracedScene>> Get(const std::string& id,
                                                         std::shared_ptr<const Scene> scene,
                                                         double* built_ms = nullptr,
                                                         const StopRequested& stop = {});
  size_t size() const;

 private:
  // One scene's slot: built under its own mutex, so other scenes are not held up.
  struct Slot {
    std::mutex mutex;
    std::shared_ptr<const TracedScene> traced;  // keeps the scene alive through its holder
  };
  struct Entry {
    std::shared_ptr<Slot> slot;
    uint64_t last_use = 0;
  };
  size_t capacity_;
  std::shared_ptr<const SharedStore> store_;
  uint64_t memory_budget_;
  mutable std::mutex mutex_;
  uint64_t clock_ = 0;
  std::map<std::string, Entry> entries_;
};

}  // namespace aperture
