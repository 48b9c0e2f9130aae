// Edge anti-aliasing filters (seed 002, eq. 2): the pixel's colour is the sum over the polygons in
// its aperture of colour x (integral of the filter over the polygon's visible part).
//
// The integral is assembled from unit "cells": a = 1 apertures are the pixel squares; a = 2
// apertures are the four unit squares centred on the pixel's corners. Per cell the coverage step
// computes the exact visible area and first moments of each polygon; the filter turns them into
// the pixel's weights here.
#pragma once

#include <cstdint>

namespace aperture {

enum class AntiAliasing { kBox1, kBox2, kTent2 };

const char* AntiAliasingName(AntiAliasing aa);

// Area and moments of a region relative to the centre of its cell: A = integral of 1,
// mx = integral of x, my = integral of y, mxy = integral of x y (x, y in [-0.5, 0.5]).
struct CellMoments {
  double area = 0, mx = 0, my = 0, mxy = 0;
};

struct AaFilterShape {
  double cell_offset;  // cell k covers [k + offset, k + offset + 1] on each axis
  int cells_per_axis;  // pixel i reads cells i .. i + cells_per_axis - 1
  double margin;       // how far the aperture reaches beyond the pixel square
  bool needs_moments;  // only the tent needs more than the area
};

inline AaFilterShape ShapeOf(AntiAliasing aa) {
  switch (aa) {
    case AntiAliasing::kBox1:
      return {0.0, 1, 0.0, false};
    case AntiAliasing::kBox2:
      return {-0.5, 2, 0.5, false};
    case AntiAliasing::kTent2:
      return {-0.5, 2, 0.5, true};
  }
  return {-0.5, 2, 0.5, false};
}

// Weight of a cell's region in the pixel whose aperture holds the cell at (cx, cy) in {0, 1}.
inline double CellWeight(AntiAliasing aa, const CellMoments& m, int cx, int cy) {
  switch (aa) {
    case AntiAliasing::kBox1:
      return m.area;
    case AntiAliasing::kBox2:
      return 0.25 * m.area;
    case AntiAliasing::kTent2: {
      // Tent (1 - |dx|)(1 - |dy|) over the 2 x 2 aperture; in the cell left of (above) the pixel
      // centre it is (0.5 + x), right of (below) it (0.5 - x), with x relative to the cell centre.
      const double sx = cx == 0 ? 1.0 : -1.0, sy = cy == 0 ? 1.0 : -1.0;
      return 0.25 * m.area + 0.5 * sx * m.mx + 0.5 * sy * m.my + sx * sy * m.mxy;
    }
  }
  return 0;
}

}  // namespace aperture
