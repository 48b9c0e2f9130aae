#include "sim_channels.h"

#include <cmath>

#include "absl/strings/str_cat.h"

namespace aperture {
namespace {

double Tan(double degrees) { return std::tan(degrees * M_PI / 180); }
double Atan(double tangent) { return std::atan(tangent) * 180 / M_PI; }

}  // namespace

absl::StatusOr<std::vector<v1::Frustum>> ChannelFrusta(const v1::Camera& base, int channels,
                                                       uint32_t width, uint32_t height) {
  if (channels < 1 || channels > 16)
    return absl::InvalidArgumentError(absl::StrCat("--channels ", channels, " must be 1..16"));
  // The base view in tangents of the view plane at distance 1.
  double left, right, bottom, top;
  if (base.has_frustum()) {
    left = Tan(base.frustum().left_deg()), right = Tan(base.frustum().right_deg());
    bottom = Tan(base.frustum().bottom_deg()), top = Tan(base.frustum().top_deg());
  } else {
    const double fov = base.vertical_fov_deg() > 0 ? base.vertical_fov_deg() : 60;
    top = Tan(fov / 2), bottom = -top;
    right = top * width / height, left = -right;
  }
  const double w = right - left, centre = (left + right) / 2;
  const double first = centre - channels * w / 2;
  std::vector<v1::Frustum> frusta;
  for (int k = 0; k < channels; ++k) {
    v1::Frustum f;
    f.set_left_deg(Atan(first + k * w));
    f.set_right_deg(Atan(first + (k + 1) * w));
    f.set_bottom_deg(Atan(bottom));
    f.set_top_deg(Atan(top));
    frusta.push_back(f);
  }
  return frusta;
}

}  // namespace aperture
