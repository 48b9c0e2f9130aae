// Visits the texels of a width x height texture in curve order, with their steps. Sub-squares of
// the enclosing 2^k square that lie wholly outside the texture are skipped, their steps still
// counted (seed 001, section 2.2), so a 1 x 65536 texture costs 65536 visits, not 2^32.
#pragma once

#include <cstdint>

#include "texture/packed/space_filling_curve.h"

namespace aperture::packed {
namespace internal {

template <typename Visitor>
void WalkSquare(Curve curve, int level, uint32_t x0, uint32_t y0, uint32_t state, uint64_t step0,
                uint32_t width, uint32_t height, Visitor& visit) {
  if (x0 >= width || y0 >= height) return;
  if (level == 0) {
    visit(static_cast<uint32_t>(step0), x0, y0);
    return;
  }
  const int half_level = level - 1;
  const uint64_t quarter = uint64_t{1} << (2 * half_level);
  for (uint32_t digit = 0; digit < 4; ++digit) {
    const auto [xb, yb, child] = ChildQuadrant(curve, state, digit);
    WalkSquare(curve, half_level, x0 + (xb << half_level), y0 + (yb << half_level), child,
               step0 + digit * quarter, width, height, visit);
  }
}

}  // namespace internal

// visit(step, x, y) for every texel, steps ascending.
template <typename Visitor>
void WalkCurve(Curve curve, uint32_t width, uint32_t height, Visitor&& visit) {
  internal::WalkSquare(curve, CurveOrder(width, height), 0, 0, 0, 0, width, height, visit);
}

}  // namespace aperture::packed
