// The visible part of a light point's footprint (render/light_pass.h): its octagon less the
// outlines of the polygons in front of the light, kept as a few convex pieces, and the exact area
// and moments of those pieces in each cell of the filter grid.
//
// A light is a few pixels across and is hidden by a few outlines at most, so cutting its octagon
// once by their edges and clipping the pieces to each cell costs a few dozen half-plane clips,
// where resolving each cell's visibility among the polygons (raster/cell_coverage.h) would redo
// the same cuts in every cell.
#pragma once

#include <span>
#include <vector>

#include "raster/aa_filter.h"
#include "raster/screen_polygon.h"
#include "scene/vec.h"

namespace aperture {

class VisibleFootprint {
 public:
  // Past this many pieces (a footprint behind a lattice of thin outlines) the cuts stop and
  // Subtract says so: the caller resolves the footprint cell by cell instead.
  static constexpr size_t kMaxPieces = 64;

  // Starts from the convex, counter-clockwise polygon `outline` (the octagon).
  void Start(std::span<const Vec2> outline);
  // Removes convex, counter-clockwise `occluder` from the pieces; false when the pieces would
  // pass kMaxPieces (the pieces are then unspecified).
  bool Subtract(const ScreenPolygon& occluder);
  bool empty() const { return pieces_.empty(); }
  // The pieces' area, square pixels.
  double Area() const;

  // The area and moments of the pieces in a row of `cells` cells: cell i is [x0 + i, x0 + i + 1]
  // x [cy - 0.5, cy + 0.5], its moments relative to its centre (x0 + i + 0.5, cy)
  // (raster/aa_filter.h's CellMoments), written to out[i]. Each piece is clipped to the row once,
  // then split at each cell's right side in turn: one cut per cell it reaches.
  void InRow(double x0, double cy, int cells, bool with_moments, CellMoments* out);
  // The pieces' area in each cell of a grid of `columns` x `rows` unit cells whose first is
  // [x0, x0 + 1] x [y0, y0 + 1], row by row into out[rows * columns]; the grid holds the pieces.
  // Area alone (the box filters'), accumulated edge by edge: each edge adds the signed area
  // between it and the grid's right side, row by row, cut exactly at the cells' sides, and the
  // sums along each row are the cells' areas (the accumulation of font-rs and of FreeType's
  // "smooth" rasterizer). A few operations per cell an edge crosses, where InRow clips every
  // piece to every cell.
  void AreasInCells(double x0, double y0, int columns, int rows, double* out);

 private:
  struct Piece {
    size_t begin, end;  // its vertices in verts_
    double min_x, min_y, max_x, max_y;
    double area;
  };
  void AddPiece(std::vector<Piece>& pieces, std::vector<Vec2>& verts, const Vec2* v, size_t n);
  // Clips a_[0, n) by a x + b y + c >= 0 into a_; returns the count left.
  size_t Clip(size_t n, double a, double b, double c, size_t capacity);

  std::vector<Piece> pieces_, next_pieces_;
  std::vector<Vec2> verts_, next_verts_;
  std::vector<Vec2> a_, b_, c_;  // clip buffers
  std::vector<double> accumulated_;
};

}  // namespace aperture
