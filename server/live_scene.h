// The scene a channel renders: the stored scene as loaded, or, once a request carries
// a SceneUpdate, the channel's own copy of it with every update applied in turn. The stored
// scene is never changed, so other clients keep seeing it as loaded. One LiveScene serves one
// RenderStream or one RenderFrame request; it holds the stored scene it renders, so the scene
// store does not drop it while the channel is open.
#pragma once

#include <functional>
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

  // The stored scene `request` names, if its update would apply to it (names, values); the check
  // stops (CANCELLED) when `stop` says so. Whoever keeps the pointer holds the scene against
  // eviction: a stream keeps it with the request until the request is rendered. No state of its
  // own: a stream's reader asks it as a request arrives while its renderer advances.
  absl::StatusOr<std::shared_ptr<const Scene>> Check(const v1::RenderFrameRequest& request,
                                                     const std::function<bool()>& stop) const;

  // The scene to render `request` with: its update applied from now on (all or nothing; on
  // error, also when `stop` says stop, the state is as before). `stored`: the scene Check gave
  // for it (null: found now). A request for another scene id starts again from that scene as
  // loaded. The stored scene is held until a request names another or this LiveScene ends.
  absl::StatusOr<std::shared_ptr<const Scene>> Advance(const v1::RenderFrameRequest& request,
                                                       std::shared_ptr<const Scene> stored,
                                                       const std::function<bool()>& stop);

  // Whether the scene Advance returned last differs from the stored one (a raytraced frame then
  // builds its own BVH instead of using the stored scene's).
  bool updated() const { return own_ != nullptr; }

 private:
  absl::StatusOr<std::shared_ptr<const Scene>> Stored(const std::string& id) const;

  SceneStore& scenes_;
  std::string id_;                       // the scene id of the last request
  std::shared_ptr<const Scene> stored_;  // that scene as loaded, held while the channel is open
  std::shared_ptr<Scene> own_;           // null until an update arrives
};

}  // namespace aperture
