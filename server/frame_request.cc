#include "frame_request.h"

#include "absl/strings/str_cat.h"

namespace aperture {

absl::StatusOr<FrameJob> ParseFrameRequest(const v1::RenderFrameRequest& request,
                                           uint64_t max_pixels, const FrameJobOptions& local) {
  auto job = FrameJobFromRequest(request, local);
  if (!job.ok()) return job.status();
  const uint64_t pixels = uint64_t{request.options().width()} * request.options().height();
  if (pixels > max_pixels)
    return absl::InvalidArgumentError(absl::StrCat(
        "options: ", request.options().width(), "x", request.options().height(), " = ", pixels,
        " pixels exceeds the server's limit of ", max_pixels, " (--max-pixels)"));
  return job;
}

}  // namespace aperture
