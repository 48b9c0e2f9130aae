// The proto's encoding options (aperture.v1.RenderOptions: pixel type and compression) as
// ExrOptions. Errors name the offending field.
#pragma once

#include "absl/status/statusor.h"
#include "aperture/v1/scene.pb.h"
#include "io/exr_writer.h"

namespace aperture {

// Pixel type and compression; DEFAULT values mean half and zip, as aperture-render writes. Float
// pixels with b44 or b44a, which compress half channels only, are INVALID_ARGUMENT.
absl::StatusOr<ExrOptions> ExrOptionsFromProto(const v1::RenderOptions& options);

}  // namespace aperture
