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
  std::vector<int> polygons;  // kMixed: polygons reaching into the window's apertures, ascending
};

struct WarnockOptions {
  // A mixed window at most this wide and high is not split further: its quadrants might still be
  // covered or empty (a horizon, a building's edge), but below this their shared border cells
  // and the splitting cost more than the fast interiors save.
  int leaf_size = 16;
  // A crowded mixed window (more than crowded_polygons polygons reach it) stops at this size
  // already: its quadrants would be mixed too, and a leaf of box2 cells computes the cells on its
  // borders that its neighbours compute again (289 cells for 256 pixels at 16, 4,225 for 4,096
  // at 64) and bins its polygons once. Crowded frames take 15-20 % less than with 16 alone,
  // frames of large polygons the same; pixels are the same at any size. The renderer
  // asks the stop test after each row of a leaf's cells.
  int crowded_leaf_size = 64;
  int crowded_polygons = 8;
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
