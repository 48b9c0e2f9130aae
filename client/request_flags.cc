#include "request_flags.h"

namespace aperture {

absl::StatusOr<v1::RenderFrameRequest> FrameRequestFromFlags(const SceneOnServer& scene) {
  auto request = FrameRequestFromFlags(scene.default_camera, scene.model_cameras);
  if (request.ok()) request->set_scene_id(scene.scene_id);
  return request;
}

}  // namespace aperture
