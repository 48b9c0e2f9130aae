// The frame request described by the command-line flags (--camera, --fov, --size, --aa, ...),
// with the same defaults as aperture-render so both render the same frame.
#pragma once

#include <cstdint>
#include <string>

#include "absl/status/statusor.h"
#include "aperture/v1/render_service.pb.h"
#include "scene_upload.h"

namespace aperture {

// "WIDTHxHEIGHT" (--size).
absl::Status ParseSize(const std::string& text, uint32_t* width, uint32_t* height);

// "X,Y,Z,YAW,PITCH,ROLL" into `camera` (other fields kept).
absl::Status ParseCameraInto(const std::string& spec, v1::Camera* camera);

// Without --camera: the scene's own camera (built-in scenes), else eye height at the origin.
absl::StatusOr<v1::RenderFrameRequest> FrameRequestFromFlags(const SceneOnServer& scene);

}  // namespace aperture
