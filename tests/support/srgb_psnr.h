// PSNR of a frame against a reference as a display shows them: each R, G and B value clamped to
// [0, 1] and sRGB-encoded (the PNG previews' transfer), peak 1; alpha is left out. Linear values
// would weigh the bright sky's errors far above the dark ground's, which a viewer does not.
#pragma once

#include <cstddef>
#include <limits>

namespace aperture::testing {

// `a` and `b`: `pixels` interleaved RGBA floats each. +infinity when they are equal after the
// encoding (a lossless codec).
double SrgbPsnr(const float* a, const float* b, size_t pixels);

inline constexpr double kLosslessPsnr = std::numeric_limits<double>::infinity();

}  // namespace aperture::testing
