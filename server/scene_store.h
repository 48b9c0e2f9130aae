// Built scenes by id, shared by the requests that render them. Bounded: past `capacity` the scene
// loaded (or used) longest ago is dropped; frames already rendering it keep their reference.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <string>

#include "scene/scene.h"

namespace aperture {

class SceneStore {
 public:
  explicit SceneStore(size_t capacity) : capacity_(capacity) {}

  void Put(const std::string& id, std::shared_ptr<const Scene> scene);
  std::shared_ptr<const Scene> Find(const std::string& id);  // null when unknown
  size_t size() const;

 private:
  struct Entry {
    std::shared_ptr<const Scene> scene;
    uint64_t last_use = 0;
  };
  size_t capacity_;
  mutable std::mutex mutex_;
  uint64_t clock_ = 0;
  std::map<std::string, Entry> scenes_;
};

}  // namespace aperture
