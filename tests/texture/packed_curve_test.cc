#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <random>
#include <vector>

#include "texture/packed/curve_walk.h"
#include "texture/packed/space_filling_curve.h"

namespace aperture::packed {
namespace {

TEST(PackedCurve, MortonIsThePapersFormula) {
  // seed 001, section 1: Z = sum_i (x_i + 2 y_i) 4^i.
  std::mt19937 rng(7);
  for (int i = 0; i < 10000; ++i) {
    const uint32_t x = rng() & 0xFFFF, y = rng() & 0xFFFF;
    uint64_t z = 0;
    for (int b = 0; b < 16; ++b) z += uint64_t(((x >> b) & 1) + 2 * ((y >> b) & 1)) << (2 * b);
    ASSERT_EQ(MortonStep(x, y), z);
    const TexelXY p = CurvePoint(Curve::kMorton, 16, static_cast<uint32_t>(z));
    ASSERT_EQ(p.x, x);
    ASSERT_EQ(p.y, y);
  }
}

TEST(PackedCurve, HilbertVisitsEveryTexelOnceWithUnitSteps) {
  for (int order = 0; order <= 7; ++order) {
    const uint32_t side = 1u << order;
    std::vector<bool> seen(size_t{side} * side, false);
    TexelXY previous{};
    for (uint32_t s = 0; s < side * side; ++s) {
      const TexelXY p = CurvePoint(Curve::kHilbert, order, s);
      ASSERT_LT(p.x, side);
      ASSERT_LT(p.y, side);
      ASSERT_FALSE(seen[size_t{p.y} * side + p.x]);
      seen[size_t{p.y} * side + p.x] = true;
      ASSERT_EQ(HilbertStep(order, p.x, p.y), s) << "order " << order;
      if (s > 0) {
        const int d = std::abs(int(p.x) - int(previous.x)) + std::abs(int(p.y) - int(previous.y));
        ASSERT_EQ(d, 1) << "order " << order << " step " << s;
      }
      previous = p;
    }
    // Starts at (0, 0) and ends at (side - 1, 0).
    EXPECT_EQ(CurvePoint(Curve::kHilbert, order, side * side - 1).x, side - 1);
    EXPECT_EQ(CurvePoint(Curve::kHilbert, order, side * side - 1).y, 0u);
  }
}

TEST(PackedCurve, HilbertRoundTripAtFullSize) {
  std::mt19937 rng(11);
  for (int order : {9, 13, 15, 16}) {
    for (int i = 0; i < 20000; ++i) {
      const uint32_t mask = (1u << order) - 1;
      const uint32_t x = rng() & mask, y = rng() & mask;
      const TexelXY p = CurvePoint(Curve::kHilbert, order, HilbertStep(order, x, y));
      ASSERT_EQ(p.x, x);
      ASSERT_EQ(p.y, y);
    }
  }
}

TEST(PackedCurve, AlignedBlocksAreContiguousStepRanges) {
  // The property the area integrals rest on.
  const int order = 5;
  for (Curve curve : {Curve::kHilbert, Curve::kMorton}) {
    for (int j = 0; j <= order; ++j) {
      const uint32_t b = 1u << j;
      for (uint32_t by = 0; by < 32; by += b) {
        for (uint32_t bx = 0; bx < 32; bx += b) {
          uint32_t lo = ~0u, hi = 0;
          for (uint32_t y = by; y < by + b; ++y) {
            for (uint32_t x = bx; x < bx + b; ++x) {
              lo = std::min(lo, CurveStep(curve, order, x, y));
              hi = std::max(hi, CurveStep(curve, order, x, y));
            }
          }
          ASSERT_EQ(hi - lo + 1, b * b);
          ASSERT_EQ(lo % (b * b), 0u);
        }
      }
    }
  }
}

TEST(PackedCurve, WalkSkipsOutsideStepsButCountsThem) {
  for (Curve curve : {Curve::kHilbert, Curve::kMorton}) {
    for (auto [w, h] : {std::pair{1u, 1u},
                        {1u, 37u},
                        {53u, 1u},
                        {37u, 91u},
                        {64u, 64u},
                        {100u, 3u},
                        {1u, 65536u}}) {
      const int order = CurveOrder(w, h);
      uint64_t count = 0;
      int64_t last = -1;
      bool ok = true;
      WalkCurve(curve, w, h, [&](uint32_t step, uint32_t x, uint32_t y) {
        ok = ok && x < w && y < h && int64_t{step} > last && step == CurveStep(curve, order, x, y);
        last = step;
        ++count;
      });
      EXPECT_TRUE(ok) << CurveName(curve) << " " << w << "x" << h;
      EXPECT_EQ(count, uint64_t{w} * h);
      EXPECT_EQ(last, int64_t{LastStepInside(curve, w, h)})
          << CurveName(curve) << " " << w << "x" << h;
    }
  }
}

TEST(PackedCurve, ParseCurveNames) {
  EXPECT_EQ(*ParseCurve("hilbert"), Curve::kHilbert);
  EXPECT_EQ(*ParseCurve("morton"), Curve::kMorton);
  EXPECT_FALSE(ParseCurve("peano").ok());
  EXPECT_EQ(CurveOrder(1, 1), 0);
  EXPECT_EQ(CurveOrder(8192, 100), 13);
  EXPECT_EQ(CurveOrder(65536, 65536), 16);
}

}  // namespace
}  // namespace aperture::packed
