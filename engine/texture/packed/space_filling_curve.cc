#include "texture/packed/space_filling_curve.h"

#include "absl/strings/str_cat.h"

namespace aperture::packed {
namespace {

constexpr std::array<uint16_t, 4 * 256> MakeHilbertNibbleTable() {
  std::array<uint16_t, 4 * 256> entries{};
  for (uint32_t state = 0; state < 4; ++state) {
    for (uint32_t x = 0; x < 16; ++x) {
      for (uint32_t y = 0; y < 16; ++y) {
        uint32_t s = state, digits = 0;
        for (int b = 3; b >= 0; --b) {
          const uint32_t xb = (x >> b) & 1u, yb = (y >> b) & 1u;
          // The digit whose quadrant is (xb, yb) under orientation s.
          for (uint32_t q = 0; q < 4; ++q) {
            const HilbertChild c = HilbertChildOf(s, q);
            if (c.xb == xb && c.yb == yb) {
              digits = (digits << 2) | q;
              s = c.state;
              break;
            }
          }
        }
        entries[(state << 8) | (x << 4) | y] = static_cast<uint16_t>((digits << 2) | s);
      }
    }
  }
  return entries;
}

}  // namespace

constexpr std::array<uint16_t, 4 * 256> kHilbertNibbleTable = MakeHilbertNibbleTable();
const char* CurveName(Curve curve) { return curve == Curve::kMorton ? "morton" : "hilbert"; }

absl::StatusOr<Curve> ParseCurve(const std::string& name) {
  if (name == "hilbert") return Curve::kHilbert;
  if (name == "morton" || name == "z") return Curve::kMorton;
  return absl::InvalidArgumentError(
      absl::StrCat("unknown curve '", name, "' (expected hilbert or morton)"));
}

int CurveOrder(uint32_t width, uint32_t height) {
  const uint32_t side = width > height ? width : height;
  int k = 0;
  while ((uint64_t{1} << k) < side) ++k;
  return k;
}

TexelXY CurvePoint(Curve curve, int order, uint32_t step) {
  TexelXY p;
  uint32_t state = 0;
  for (int level = order - 1; level >= 0; --level) {
    const uint32_t digit = (step >> (2 * level)) & 3u;
    const auto [xb, yb, child] = ChildQuadrant(curve, state, digit);
    state = child;
    p.x |= xb << level;
    p.y |= yb << level;
  }
  return p;
}

uint32_t LastStepInside(Curve curve, uint32_t width, uint32_t height) {
  const int order = CurveOrder(width, height);
  uint32_t x0 = 0, y0 = 0, state = 0;
  uint64_t step = 0;
  for (int level = order - 1; level >= 0; --level) {
    // The last of the four sub-squares (in curve order) that holds texels of the texture.
    for (int digit = 3; digit >= 0; --digit) {
      const auto [xb, yb, child] = ChildQuadrant(curve, state, static_cast<uint32_t>(digit));
      const uint32_t cx = x0 + (xb << level), cy = y0 + (yb << level);
      if (cx < width && cy < height) {
        x0 = cx;
        y0 = cy;
        state = child;
        step += static_cast<uint64_t>(digit) << (2 * level);
        break;
      }
    }
  }
  return static_cast<uint32_t>(step);
}

}  // namespace aperture::packed
