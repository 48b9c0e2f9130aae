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

// How a frame is made: the Warnock rasterizer, or seed 003's reverse ray tracing (issue 7).
enum class RenderMode { kRaster, kRaytrace };
absl::StatusOr<RenderMode> ParseRenderMode(const std::string& name);  // "raster", "raytrace"

}  // namespace aperture
