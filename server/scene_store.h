// Built scenes by id, shared by the requests that render them. Bounded: past `capacity` the scene
// loaded (or used) longest ago is dropped; frames already rendering it keep their reference.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>

#include "aperture/v1/scene.pb.h"
#include "scene/scene.h"

namespace aperture {

class SceneStore {
 public:
  explicit SceneStore(size_t capacity) : capacity_(capacity) {}

  // `default_camera`: a built-in scene's, given back by Find so that a repeated LoadScene of the
  // same request answers from here without building the scene again.
  void Put(const std::string& id, std::shared_ptr<const Scene> scene,
           std::optional<v1::Camera> default_camera = std::nullopt);
  // Null when unknown.
  std::shared_ptr<const Scene> Find(const std::string& id,
                                    std::optional<v1::Camera>* default_camera = nullptr);
  size_t size() const;

 private:
  struct Entry {
    std::shared_ptr<const Scene> scene;
    std::optional<v1::Camera> default_camera;
    uint64_t last_use = 0;
  };
  size_t capacity_;
  mutable std::mutex mutex_;
  uint64_t clock_ = 0;
  std::map<std::string, Entry> scenes_;
};

}  // namespace aperture
