// Warnock-style screen subdivision: a window is split into quadrants until it is empty, fully
// covered by one polygon in front of all others, or small. Leaves are the units of parallel work.
#pragma once

#include <vector>

#include "base/pixel_rect.h"
#include "raster/aa_filter.h"
#include "raster/projection.h"

namespace aperture {

struct LeafWindow {
  enum class Kind { kEmpty, kCovered, kMixed };
  PixelRect rect;
  Kind kind = Kind::kEmpty;
  int cover = -1;             // kCovered: the polygon seen in every aperture of the window
  std::vector<int> polygons;  // kMixed: polygons reaching into the window's apertures
};

struct WarnockOptions {
  // A mixed window at most this wide and high is not split further. 16 rather than 8: a leaf of
  // box2 cells also computes the cells on its borders, which its neighbours compute again (81 for
  // 64 pixels at 8, 289 for 256 at 16); crowded frames take 8-10 % less, pixels are the same
  // (issue 19).
  int leaf_size = 16;
};

// Subdivides one window whose candidate polygons are known, appending its leaves.
void SubdivideWindow(const FrameGeometry& geometry, const AaFilterShape& aa,
                     const WarnockOptions& options, const PixelRect& window,
                     const std::vector<int>& candidates, std::vector<LeafWindow>& leaves);

// Polygons whose bounding boxes (widened by the filter margin) reach each `tile` x `tile` window
// of `region`, row by row; `columns` receives the number of windows per row.
std::vector<std::vector<int>> BinPolygons(const FrameGeometry& geometry, double margin,
                                          const PixelRect& region, int tile, int* columns);

// Does convex `polygon` reach into the rectangle [x0, x1] x [y0, y1]?
bool PolygonOverlapsRect(const ScreenPolygon& polygon, double x0, double y0, double x1, double y1);

}  // namespace aperture
