// Parsing of the option values shared by the command-line tools.
#pragma once

#include <string>

#include "absl/status/statusor.h"
#include "raster/aa_filter.h"
#include "texture/texture_sampler.h"

namespace aperture {

struct ImageSize {
  int width = 0, height = 0;
};

absl::StatusOr<ImageSize> ParseImageSize(const std::string& text);  // "1920x1080"
absl::StatusOr<AntiAliasing> ParseAntiAliasing(const std::string& name);
absl::StatusOr<FilterMode> ParseFilterMode(const std::string& name);

}  // namespace aperture
