// A RenderFrameRequest as the engine's job (engine/frame/frame_job.h), within the server's pixel
// limit, with the server's own choices for it (`local`: its frame memory budget).
#pragma once

#include <cstdint>

#include "absl/status/statusor.h"
#include "aperture/v1/render_service.pb.h"
#include "frame/frame_job.h"

namespace aperture {

absl::StatusOr<FrameJob> ParseFrameRequest(const v1::RenderFrameRequest& request,
                                           uint64_t max_pixels, const FrameJobOptions& local = {});

}  // namespace aperture
