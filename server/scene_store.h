// Built scenes by id, shared by the requests that render them. Bounded by count and by bytes:
// a load reserves its scene's estimated bytes before it builds; to make room
// (bytes or count) the scenes no frame or stream holds are dropped, least recently used first. A
// scene is held while someone keeps the pointer Find gave: a frame while it renders, a
// RenderStream from its first request naming the scene until the stream ends, so a stream's scene
// is never dropped under it. While every scene is held, a load past the byte budget is refused
// and one past the count is kept until a scene is let go.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>

#include "absl/status/statusor.h"
#include "aperture/v1/scene.pb.h"
#include "byte_budget.h"
#include "scene/scene.h"

namespace aperture {

class SceneStore {
 public:
  // `budget_bytes`: what all loaded scenes may hold together (--max-scenes-mb).
  SceneStore(size_t capacity, uint64_t budget_bytes)
      : capacity_(capacity), budget_("loaded scenes (--max-scenes-mb)", budget_bytes) {}

  // Room for a scene of `bytes` (`what` says how they add up): RESOURCE_EXHAUSTED naming the
  // budget when the scene alone exceeds it, or when the scenes in use leave no room.
  absl::StatusOr<ByteReservation> Reserve(uint64_t bytes, const std::string& what);
  // `room`: the scene's reservation, held as long as the scene is. `default_camera`: a built-in
  // scene's, given back by Find so that a repeated LoadScene of the same request answers from
  // here without building the scene again.
  void Put(const std::string& id, std::shared_ptr<const Scene> scene,
           std::optional<v1::Camera> default_camera, ByteReservation room);
  // Null when unknown.
  std::shared_ptr<const Scene> Find(const std::string& id,
                                    std::optional<v1::Camera>* default_camera = nullptr);
  size_t size() const;
  uint64_t bytes() const { return budget_.used(); }
  uint64_t budget() const { return budget_.limit(); }
  uint64_t evicted() const;

 private:
  struct Entry {
    std::shared_ptr<const Scene> scene;
    std::optional<v1::Camera> default_camera;
    uint64_t last_use = 0;
    ByteReservation room;
  };
  // Drops the least recently used scene nobody else holds, other than `keep`; false when there is
  // none.
  bool EvictOne(const std::string& keep = {});

  const size_t capacity_;
  ByteBudget budget_;
  mutable std::mutex mutex_;
  uint64_t clock_ = 0, evicted_ = 0;
  std::map<std::string, Entry> scenes_;
};

}  // namespace aperture
