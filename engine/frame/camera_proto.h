// The camera in its proto form and back.
#pragma once

#include "absl/status/statusor.h"
#include "aperture/v1/scene.pb.h"
#include "scene/camera.h"

namespace aperture {

// Camera from its proto form (defaults: fov 60, near 0.1), validated.
absl::StatusOr<Camera> CameraFromProto(const v1::Camera& proto);
v1::Camera CameraToProto(const Camera& camera);

}  // namespace aperture
