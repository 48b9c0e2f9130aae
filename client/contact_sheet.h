// The contact sheet `aperture batch` writes next to its frames: small thumbnails of the frames in
// a grid, each with its frame number, as an 8-bit sRGB PNG, so that a person sees the whole job
// at a glance.
#pragma once

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "absl/status/status.h"

namespace aperture {

// `frames`: (frame number, EXR path) in order. At most kMaxThumbnails are shown (evenly spaced
// through the job); frames that do not read are drawn as a dark grey cell.
inline constexpr size_t kMaxThumbnails = 400;
absl::Status WriteContactSheet(const std::vector<std::pair<size_t, std::string>>& frames,
                               const std::string& png_path, int thumbnail_width = 160);

}  // namespace aperture
