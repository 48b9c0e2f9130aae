// Which of two polygons is seen where they overlap: the nearer one, and where their depths are
// equal (coplanar polygons: runway markings painted over the pavement, a sticker on a skin, the
// same mesh placed twice) the one drawn over the other by the scene's rule, as image generators
// draw decals: the higher `Object.layer`, then the later in the scene's order (docs/SCENE.md,
// "Coplanar polygons"). Every visibility test of the rasterizer (Warnock covers, a cell's exact
// coverage) and the tests' dense-sampling references decide by these functions, so a tie is
// resolved the same way everywhere and a stack of coplanar polygons has one painter's order.
#pragma once

#include <cmath>
#include <cstdint>
#include <cstring>
#include <span>

namespace aperture {

// Inverse depths closer than this, relative to their size, are equal: far above the rounding of
// planes computed from different vertices of one plane (about 1e-15), far below what separates
// modelled surfaces (a decal lifted 1 mm at 10 km is 1e-7 apart).
inline constexpr double kCoplanarTolerance = 1e-9;

// +1 where inverse depth `a` is nearer than `b`, -1 where farther, 0 where they are equal within
// the tolerance.
inline int DepthSign(double a, double b) {
  const double tolerance = kCoplanarTolerance * (std::abs(a) + std::abs(b));
  return a > b + tolerance ? 1 : b > a + tolerance ? -1 : 0;
}

// A positive inverse depth to within about the coplanar tolerance: its exponent and leading 30
// bits of mantissa (2^-30 is 9.3e-10), which order as the values do. Sorting nearest first by it,
// ties drawn last first, puts a stack of coplanar layers in the order they hide one another.
inline uint64_t NearestQuantum(double inverse_depth) {
  uint64_t bits;
  std::memcpy(&bits, &inverse_depth, sizeof bits);
  return bits >> 22;
}

// The order in which coplanar polygons are drawn: a later one is drawn over an earlier one.
// `index` is the polygon's position in the frame, which follows the scene's order.
inline int64_t DrawOrder(int layer, int index) {
  return static_cast<int64_t>(layer) * (int64_t{1} << 32) + index;
}

// Whether surface A, wherever it overlaps surface B inside a convex region, is seen and B hidden,
// given the signs DepthSign(A, B) at the region's corners (or at the vertices of both pieces):
// A nowhere behind B and either somewhere in front of it or drawn over it. Depth differences are
// linear, so the corners bound them over the region; a tie at a corner where A is otherwise in
// front (a wall standing on the ground) leaves B at most a sliver of the tolerance's width.
inline bool HidesAt(std::span<const int> signs, bool a_drawn_over_b) {
  bool in_front = false;
  for (int s : signs) {
    if (s < 0) return false;
    in_front = in_front || s > 0;
  }
  return in_front || a_drawn_over_b;
}

}  // namespace aperture
