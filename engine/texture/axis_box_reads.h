// The axis-aligned box read exactly (issue 22, session 40): the mean of the bilinear base over
// [c - h, c + h] along one texture axis, for a half-width h under a texel, as two bilinear reads.
//
// Along one axis the bilinear texture is sum_k t_k tent(x - k - 1/2) (texel centres at +1/2), so
// the box's mean weighs texel k by the mean of tent(x - k - 1/2) over the box. The tent is
// ramp(y + 1) - 2 ramp(y) + ramp(y - 1) with ramp(y) = max(y, 0), and the mean of the ramp over
// [y - h, y + h] is
//   R(y) = (z + h)^2 / (4 h) + max(y - h, 0),  z = clamp(y, -h, h),
// (0 below, y above, the parabola between), which has no cancellation however small h is. With
// h < 1 the box and the tent reach at most four texel centres, x0 + 1/2 .. x0 + 7/2 with
// x0 = floor(c - 1/2) - 1; their weights are W_k = R_k - 2 R_(k+1) + R_(k+2) with
// R_j = R(c - x0 - 1/2 + 1 - j). Texels k and k + 1 are then one bilinear read between their
// centres, at the fraction W_(k+1) / (W_k + W_(k+1)) with the weight W_k + W_(k+1) (both sums
// are positive: the second and third centres lie within a texel of c). A separable box in 2D is
// the product: four bilinear reads.
//
// AxisBoxPairs is the portable code; aniso_lane_reads.cc has its AVX2 twin (AxisBoxPairsAvx2),
// the same operations in the same order, so both give the same bits.
#pragma once

#include <algorithm>
#include <cmath>

namespace aperture {

// For the box of half-width `half` (texels, 0 < half < 1) centred at `c` (texels: the sample's
// coordinate times the texture's size): the two reads' coordinates, in repeats (times
// `inv_size`), and their weights, which sum to 1 (up to rounding).
inline void AxisBoxPairs(float c, float half, float inv_size, float position[2], float weight[2]) {
  const float x0 = std::floor(c - 0.5f) - 1.0f;
  const float a0 = c - x0 - 0.5f;
  const float inv_4h = 1.0f / (4.0f * half);
  float R[6];
  for (int j = 0; j < 6; ++j) {
    const float y = a0 + (1.0f - static_cast<float>(j));
    const float z = std::min(std::max(y, -half), half) + half;
    R[j] = z * z * inv_4h + std::max(y - half, 0.0f);
  }
  for (int p = 0; p < 2; ++p) {
    const float w0 = (R[2 * p] - 2.0f * R[2 * p + 1]) + R[2 * p + 2];
    const float w1 = (R[2 * p + 1] - 2.0f * R[2 * p + 2]) + R[2 * p + 3];
    const float sum = w0 + w1;
    weight[p] = sum;
    position[p] = (x0 + (0.5f + 2.0f * static_cast<float>(p)) + w1 / sum) * inv_size;
  }
}

}  // namespace aperture
