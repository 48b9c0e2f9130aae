#include "live_scene.h"

#include "absl/strings/str_cat.h"
#include "scene/scene_update.h"
#include "scene_id.h"

namespace aperture {
namespace {

// A scene id is 64 hex digits; a longer one is quoted only this far in the error.
constexpr size_t kQuotedIdChars = 64;

}  // namespace

absl::StatusOr<std::shared_ptr<const Scene>> LiveScene::Stored(const std::string& id) const {
  if (absl::Status form = CheckSceneId(id); !form.ok()) return form;
  std::shared_ptr<const Scene> scene = scenes_.Find(id);
  if (!scene)
    return absl::NotFoundError(absl::StrCat("scene_id '", id.substr(0, kQuotedIdChars),
                                            id.size() > kQuotedIdChars ? "...'" : "'",
                                            " is not loaded (LoadScene first)"));
  return scene;
}

absl::StatusOr<std::shared_ptr<const Scene>> LiveScene::Check(
    const v1::RenderFrameRequest& request, const std::function<bool()>& stop) const {
  auto scene = Stored(request.scene_id());
  if (!scene.ok() || !request.has_update()) return scene;
  if (auto s = CheckSceneUpdate(**scene, request.update(), stop); !s.ok()) return s;
  return scene;
}

absl::StatusOr<std::shared_ptr<const Scene>> LiveScene::Advance(
    const v1::RenderFrameRequest& request, std::shared_ptr<const Scene> stored,
    const std::function<bool()>& stop) {
  if (!stored) {
    auto found = Stored(request.scene_id());
    if (!found.ok()) return found.status();
    stored = *std::move(found);
  }
  if (request.scene_id() != id_) {
    id_ = request.scene_id();
    own_ = nullptr;
  }
  stored_ = std::move(stored);
  if (!own_ && !request.has_update()) return stored_;
  if (!own_) own_ = std::make_shared<Scene>(*stored_);  // polygons copied once; textures shared
  // A frame that still holds the last state (none today: frames are rendered one at a time)
  // keeps it; the update goes to a copy.
  if (own_.use_count() > 1) own_ = std::make_shared<Scene>(*own_);
  if (request.has_update())
    if (auto s = ApplySceneUpdate(request.update(), own_.get(), stop); !s.ok()) return s;
  return std::shared_ptr<const Scene>(own_);
}

}  // namespace aperture
