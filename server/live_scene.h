// The scene a channel renders (issue 20): the stored scene as loaded, or, once a request carries
// a SceneUpdate, the channel's own copy of it with every update applied in turn. The stored
// scene is never changed, so other clients keep seeing it as loaded. One LiveScene serves one
// RenderStream (its renderer thread) or one RenderFrame request.
#pragma once

#include <memory>
#include <string>

#include "absl/status/statusor.h"
#include "aperture/v1/render_service.pb.h"
#include "scene/scene.h"
#include "scene_store.h"

namespace aperture {

class LiveScene {
 public:
  explicit LiveScene(SceneStore& scenes) : scenes_(scenes) {}

  // Whether `request` names a loaded scene and its update would apply to it (names, values).
  // Cheap, no state: a stream asks it as a request arrives.
  absl::Status Check(const v1::RenderFrameRequest& request) const;

  // The scene to render `request` with: its update applied from now on (all or nothing; on
  // error the state is as before). A request for another scene id starts again from that scene
  // as loaded.
  absl::StatusOr<std::shared_ptr<const Scene>> Advance(const v1::RenderFrameRequest& request);

  // Whether the scene Advance returned last differs from the stored one (a raytraced frame then
  // builds its own BVH instead of using the stored scene's).
  bool updated() const { return own_ != nullptr; }

 private:
  absl::StatusOr<std::shared_ptr<const Scene>> Stored(const std::string& id) const;

  SceneStore& scenes_;
  std::string id_;              // the scene id of the last request
  std::shared_ptr<Scene> own_;  // null until an update arrives
};

}  // namespace aperture
