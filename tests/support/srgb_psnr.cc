#include "support/srgb_psnr.h"

#include <algorithm>
#include <cmath>

namespace aperture::testing {
namespace {

// IEC 61966-2-1's encoding, as io/exr_writer's PNG preview applies it.
double SrgbEncode(float linear) {
  const double v = std::clamp(static_cast<double>(linear), 0.0, 1.0);
  return v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055;
}

}  // namespace

double SrgbPsnr(const float* a, const float* b, size_t pixels) {
  double squared = 0;
  for (size_t p = 0; p < pixels; ++p)
    for (int c = 0; c < 3; ++c) {
      const double d = SrgbEncode(a[4 * p + c]) - SrgbEncode(b[4 * p + c]);
      squared += d * d;
    }
  if (squared == 0 || pixels == 0) return kLosslessPsnr;
  const double mse = squared / (3.0 * static_cast<double>(pixels));
  return 10.0 * std::log10(1.0 / mse);
}

}  // namespace aperture::testing
