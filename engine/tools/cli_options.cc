#include "tools/cli_options.h"

#include <cstdlib>

#include "absl/strings/str_cat.h"

namespace aperture {

absl::StatusOr<ImageSize> ParseImageSize(const std::string& text) {
  const size_t x = text.find('x');
  auto number = [](const std::string& s, int* out) {
    if (s.empty() || s.size() > 9 || s.find_first_not_of("0123456789") != std::string::npos)
      return false;
    *out = std::atoi(s.c_str());
    return true;
  };
  ImageSize size;
  if (x == std::string::npos || !number(text.substr(0, x), &size.width) ||
      !number(text.substr(x + 1), &size.height))
    return absl::InvalidArgumentError(
        absl::StrCat("size '", text, "' must be WIDTHxHEIGHT, e.g. 1920x1080"));
  return size;
}

absl::StatusOr<RenderMode> ParseRenderMode(const std::string& name) {
  if (name == "raster") return RenderMode::kRaster;
  if (name == "raytrace") return RenderMode::kRaytrace;
  return absl::InvalidArgumentError(
      absl::StrCat("unknown render mode '", name, "' (raster, raytrace)"));
}

absl::StatusOr<AntiAliasing> ParseAntiAliasing(const std::string& name) {
  for (AntiAliasing aa : {AntiAliasing::kBox1, AntiAliasing::kBox2, AntiAliasing::kTent2})
    if (name == AntiAliasingName(aa)) return aa;
  return absl::InvalidArgumentError(
      absl::StrCat("unknown anti-aliasing '", name, "' (box1, box2, tent2)"));
}

absl::StatusOr<FilterMode> ParseFilterMode(const std::string& name) {
  for (FilterMode m : {FilterMode::kNearest, FilterMode::kBilinear, FilterMode::kTrilinear,
                       FilterMode::kAniso, FilterMode::kOiio, FilterMode::kReference})
    if (name == FilterModeName(m)) return m;
  return absl::InvalidArgumentError(
      absl::StrCat("unknown texture filter '", name,
                   "' (nearest, bilinear, trilinear, aniso, oiio, reference)"));
}

}  // namespace aperture
