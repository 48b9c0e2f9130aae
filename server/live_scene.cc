#include "live_scene.h"

#include "absl/strings/str_cat.h"
#include "scene/scene_update.h"
#include "scene_id.h"

namespace aperture {

absl::StatusOr<std::shared_ptr<const Scene>> LiveScene::Stored(const std::string& id) const {
  if (absl::Status form = CheckSceneId(id); !form.ok()) return form;
  std::shared_ptr<const Scene> scene = scenes_.Find(id);
  if (!scene)
    return absl::NotFoundError(absl::StrCat("scene_id '", id, "' is not loaded (LoadScene first)"));
  return scene;
}

absl::Status LiveScene::Check(const v1::RenderFrameRequest& request) const {
  auto scene = Stored(request.scene_id());
  if (!scene.ok()) return scene.status();
  return request.has_update() ? CheckSceneUpdate(**scene, request.update()) : absl::OkStatus();
}

absl::StatusOr<std::shared_ptr<const Scene>> LiveScene::Advance(
    const v1::RenderFrameRequest& request) {
  if (request.scene_id() != id_) {
    id_ = request.scene_id();
    own_ = nullptr;
  }
  if (!own_ && !request.has_update()) return Stored(id_);
  if (!own_) {
    auto stored = Stored(id_);
    if (!stored.ok()) return stored.status();
    own_ = std::make_shared<Scene>(**stored);  // polygons copied once; textures shared
  }
  // A frame that still holds the last state (none today: frames are rendered one at a time)
  // keeps it; the update goes to a copy.
  if (own_.use_count() > 1) own_ = std::make_shared<Scene>(*own_);
  if (request.has_update())
    if (auto s = ApplySceneUpdate(request.update(), own_.get()); !s.ok()) return s;
  return std::shared_ptr<const Scene>(own_);
}

}  // namespace aperture
