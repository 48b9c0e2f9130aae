// The proto's render options (aperture.v1.RenderOptions) as the engine's settings: what to render
// (RenderSettings) and how to encode it (ExrOptions). Errors name the offending field.
#pragma once

#include "absl/status/statusor.h"
#include "aperture/v1/scene.pb.h"
#include "io/exr_writer.h"
#include "render/frame_renderer.h"

namespace aperture {

// Size, edge anti-aliasing, texture filter override and aperture; `threads` is left at 0 (the
// caller's arena) and `region` empty (the whole frame).
// Width and height are required (1..kMaxImageSide); texture_aperture 0 means the default, 2.
absl::StatusOr<RenderSettings> RenderSettingsFromProto(const v1::RenderOptions& options);

// Pixel type and compression; DEFAULT values mean half and zip, as aperture-render writes.
absl::StatusOr<ExrOptions> ExrOptionsFromProto(const v1::RenderOptions& options);

}  // namespace aperture
