// Exact area and first moments of a polygon (Green's theorem), for analytic filter integrals.
#pragma once

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

inline void Accumulate(CellMoments& sum, const CellMoments& m) {
  sum.area += m.area;
  sum.mx += m.mx;
  sum.my += m.my;
  sum.mxy += m.mxy;
}

}  // namespace aperture
