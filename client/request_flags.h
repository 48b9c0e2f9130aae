// The frame request the command-line flags describe for a scene on the server: common/frame_flags.h
// (the flags aperture-render shares, so both render the same frame) with the scene's id and
// cameras.
#pragma once

#include "absl/status/statusor.h"
#include "aperture/v1/render_service.pb.h"
#include "frame_flags.h"
#include "scene_upload.h"

namespace aperture {

absl::StatusOr<v1::RenderFrameRequest> FrameRequestFromFlags(const SceneOnServer& scene);

}  // namespace aperture
