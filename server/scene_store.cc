#include "scene_store.h"

#include "absl/strings/str_cat.h"
#include "refusal_log.h"

namespace aperture {

bool SceneStore::EvictOne(const std::string& keep) {
  auto oldest = scenes_.end();
  for (auto it = scenes_.begin(); it != scenes_.end(); ++it)
    if (it->second.scene.use_count() == 1 &&  // no frame, stream or load holds it
        it->first != keep &&
        (oldest == scenes_.end() || it->second.last_use < oldest->second.last_use))
      oldest = it;
  if (oldest == scenes_.end()) return false;
  scenes_.erase(oldest);  // returns its bytes to the budget
  ++evicted_;
  return true;
}

absl::StatusOr<ByteReservation> SceneStore::Reserve(uint64_t bytes, const std::string& what) {
  std::lock_guard lock(mutex_);
  while (true) {
    auto room = budget_.Reserve(bytes);
    if (room.ok()) return room;
    if (bytes > budget_.limit() || !EvictOne())
      return MarkRefusal(absl::ResourceExhaustedError(absl::StrCat(
                             "the scene would hold about ", what, ": ", room.status().message())),
                         RefusalKind(room.status()).value_or("over the loaded scenes' budget"));
  }
}

void SceneStore::Put(const std::string& id, std::shared_ptr<const Scene> scene,
                     std::optional<v1::Camera> default_camera, ByteReservation room) {
  std::lock_guard lock(mutex_);
  scenes_[id] = {std::move(scene), std::move(default_camera), ++clock_, std::move(room)};
  // Held scenes stay: past the count only while streams and frames hold every other one.
  while (scenes_.size() > capacity_ && EvictOne(id)) {
  }
}

std::shared_ptr<const Scene> SceneStore::Find(const std::string& id,
                                              std::optional<v1::Camera>* default_camera) {
  std::lock_guard lock(mutex_);
  auto it = scenes_.find(id);
  if (it == scenes_.end()) return nullptr;
  it->second.last_use = ++clock_;
  if (default_camera != nullptr) *default_camera = it->second.default_camera;
  return it->second.scene;
}

size_t SceneStore::size() const {
  std::lock_guard lock(mutex_);
  return scenes_.size();
}

uint64_t SceneStore::evicted() const {
  std::lock_guard lock(mutex_);
  return evicted_;
}

}  // namespace aperture
