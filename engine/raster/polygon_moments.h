// Exact area and first moments of a polygon (Green's theorem), for analytic filter integrals.
#pragma once

#include <algorithm>
#include <cmath>
#include <span>

#include "raster/aa_filter.h"
#include "scene/vec.h"

namespace aperture {

// Counter-clockwise (positive signed area) polygon; coordinates relative to the cell centre.
inline CellMoments PolygonMoments(std::span<const Vec2> p, bool with_moments) {
  CellMoments m;
  const size_t n = p.size();
  for (size_t i = 0; i < n; ++i) {
    const Vec2& a = p[i];
    const Vec2& b = p[i + 1 == n ? 0 : i + 1];
    const double c = a.x * b.y - b.x * a.y;
    m.area += c;
    if (with_moments) {
      m.mx += (a.x + b.x) * c;
      m.my += (a.y + b.y) * c;
      m.mxy += (a.x * b.y + 2 * a.x * a.y + 2 * b.x * b.y + b.x * a.y) * c;
    }
  }
  m.area *= 0.5;
  m.mx *= 1.0 / 6.0;
  m.my *= 1.0 / 6.0;
  m.mxy *= 1.0 / 24.0;
  return m;
}

// Area of the part of the unit cell [-0.5, 0.5]^2 where a x + b y + c >= 0, in closed form: the
// cell's one polygon crossed by one edge (most edge cells of a sparse frame) without clipping.
// Reflecting x or y keeps the area, so with A = |a| <= B = |b| (or swapped) it is the area of
// A u + B v <= s over the unit square (u, v in [0, 1]), s = (A + B) / 2 + c: a corner triangle
// s^2 / 2AB while s < A, a band (2s - A) / 2B up to B, then the square less the opposite triangle.
// No branch divides by the smaller slope, so nearly axis-parallel lines are as exact as any.
inline double HalfPlaneCellArea(double a, double b, double c) {
  const double lo = std::min(std::abs(a), std::abs(b)), hi = std::max(std::abs(a), std::abs(b));
  const double s = 0.5 * (lo + hi) + c;
  if (s <= 0) return 0;
  if (s >= lo + hi) return 1;
  if (s < lo) return s * s / (2 * lo * hi);
  if (s <= hi) return (2 * s - lo) / (2 * hi);
  const double t = lo + hi - s;
  return 1 - t * t / (2 * lo * hi);
}

inline void Accumulate(CellMoments& sum, const CellMoments& m) {
  sum.area += m.area;
  sum.mx += m.mx;
  sum.my += m.my;
  sum.mxy += m.mxy;
}

}  // namespace aperture
