#include "scene_store.h"

namespace aperture {

void SceneStore::Put(const std::string& id, std::shared_ptr<const Scene> scene,
                     std::optional<v1::Camera> default_camera) {
  std::lock_guard lock(mutex_);
  scenes_[id] = {std::move(scene), std::move(default_camera), ++clock_};
  while (scenes_.size() > capacity_) {
    auto oldest = scenes_.begin();
    for (auto it = scenes_.begin(); it != scenes_.end(); ++it)
      if (it->second.last_use < oldest->second.last_use) oldest = it;
    scenes_.erase(oldest);
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

}  // namespace aperture
