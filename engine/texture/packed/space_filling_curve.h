// Space-filling curves over a 2^k x 2^k square (seed 001, section 1): Hilbert and Morton (Z).
//
// Steps are numbered from 0 here. The paper numbers them from 1 (its table 3 ends at 64 on an 8x8
// texture); 0-based steps keep the last step of a 65536 x 65536 texture inside a uint32, which the
// paper demands ("4 bytes per step ... 65536x65536").
#pragma once

#include <array>
#include <cstdint>
#include <string>

#include "absl/status/statusor.h"

namespace aperture::packed {

enum class Curve : uint8_t { kHilbert = 0, kMorton = 1 };

inline constexpr uint32_t kMaxTextureSide = 65536;  // seed 001, section 2.5

const char* CurveName(Curve curve);
absl::StatusOr<Curve> ParseCurve(const std::string& name);

// Smallest k with 2^k >= max(width, height): the curve's order.
int CurveOrder(uint32_t width, uint32_t height);

// Morton step, seed 001, section 1: Z = sum_i (x_i + 2 y_i) 4^i.
inline uint32_t SpreadBits16(uint32_t v) {
  v &= 0xFFFFu;
  v = (v | (v << 8)) & 0x00FF00FFu;
  v = (v | (v << 4)) & 0x0F0F0F0Fu;
  v = (v | (v << 2)) & 0x33333333u;
  v = (v | (v << 1)) & 0x55555555u;
  return v;
}
inline uint32_t MortonStep(uint32_t x, uint32_t y) {
  return SpreadBits16(x) | (SpreadBits16(y) << 1);
}

// Hilbert step of (x, y) on the order-`order` curve (the curve of Hacker's Delight / Wikipedia's
// xy2d: starts at (0, 0), ends at (2^k - 1, 0)).
// Four levels per lookup in a 2 KiB table: index (orientation << 8) | (x nibble << 4) | y nibble,
// value (8 step bits << 2) | new orientation. (Measured faster here than the bit-parallel
// prefix-scan formulation, which costs about 90 instructions per step.)
extern const std::array<uint16_t, 4 * 256> kHilbertNibbleTable;
inline uint32_t HilbertStep(int order, uint32_t x, uint32_t y) {
  // Pad the order up to a multiple of 4. Each leading zero level of a Hilbert curve only toggles
  // the swap bit, so starting from orientation (padding & 1) gives the order-`order` curve.
  const int levels = (order + 3) & ~3;
  uint32_t state = static_cast<uint32_t>(levels - order) & 1u;
  uint32_t step = 0;
  for (int shift = levels - 4; shift >= 0; shift -= 4) {
    const uint32_t e =
        kHilbertNibbleTable[(state << 8) | (((x >> shift) & 15u) << 4) | ((y >> shift) & 15u)];
    step = (step << 8) | (e >> 2);
    state = e & 3u;
  }
  return step;
}

inline uint32_t CurveStep(Curve curve, int order, uint32_t x, uint32_t y) {
  return curve == Curve::kMorton ? MortonStep(x, y) : HilbertStep(order, x, y);
}

struct TexelXY {
  uint32_t x = 0, y = 0;
};
// Inverse of CurveStep.
TexelXY CurvePoint(Curve curve, int order, uint32_t step);

// The step of the last texel of a width x height texture along the curve over its enclosing square
// (steps outside a non-square texture are skipped but counted, seed 001, section 2.2).
uint32_t LastStepInside(Curve curve, uint32_t width, uint32_t height);

// One level of the Hilbert recursion. The orientation of a sub-square is an element of the Klein
// group {identity, swap x<->y, complement both, both}: bit 0 = swap, bit 1 = complement. The
// curve-local quadrant (rx, ry) of digit q = (3 rx) xor ry lies at T(rx, ry) in texture axes and
// its sub-square has orientation T xor R(rx, ry).
struct HilbertChild {
  uint32_t xb, yb;  // quadrant in texture axes (0 or 1 each)
  uint32_t state;   // orientation of the sub-square
};
constexpr HilbertChild HilbertChildOf(uint32_t state, uint32_t digit) {
  const uint32_t rx = digit >> 1;
  const uint32_t ry = (digit ^ rx) & 1u;
  const uint32_t rotation = ry ? 0u : (rx ? 3u : 1u);
  uint32_t xb = rx ^ (state >> 1), yb = ry ^ (state >> 1);
  if (state & 1u) {
    const uint32_t swapped = xb;
    xb = yb;
    yb = swapped;
  }
  return {xb, yb, state ^ rotation};
}

// The digit whose Hilbert quadrant in a sub-square of orientation `state` is (xb, yb): the inverse
// of HilbertChildOf, by table rather than by trying the four digits.
struct HilbertDigits {
  uint32_t digit[4][4];  // [state][yb * 2 + xb]
};
constexpr HilbertDigits MakeHilbertDigits() {
  HilbertDigits t{};
  for (uint32_t state = 0; state < 4; ++state) {
    for (uint32_t digit = 0; digit < 4; ++digit) {
      const HilbertChild c = HilbertChildOf(state, digit);
      t.digit[state][c.yb * 2 + c.xb] = digit;
    }
  }
  return t;
}
inline constexpr HilbertDigits kHilbertDigits = MakeHilbertDigits();

// Quadrant `digit` of a sub-square in either curve (Morton: x bit, y bit; no orientation).
constexpr HilbertChild ChildQuadrant(Curve curve, uint32_t state, uint32_t digit) {
  if (curve == Curve::kMorton) return {digit & 1u, digit >> 1, state};
  return HilbertChildOf(state, digit);
}

}  // namespace aperture::packed
