#include "render/visible_footprint.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "raster/polygon_clip.h"
#include "raster/polygon_moments.h"

namespace aperture {
namespace {

// A piece smaller than this (square pixels) is dropped: the sliver rounding leaves along an
// occluder's edge, far below any pixel value's resolution.
constexpr double kSliverArea = 1e-12;

double TwiceSignedArea(const Vec2* v, size_t n) {
  double s = 0;
  for (size_t i = 0; i < n; ++i) {
    const Vec2& p = v[i];
    const Vec2& q = v[i + 1 == n ? 0 : i + 1];
    s += p.x * q.y - q.x * p.y;
  }
  return s;
}

}  // namespace

void VisibleFootprint::AddPiece(std::vector<Piece>& pieces, std::vector<Vec2>& verts, const Vec2* v,
                                size_t n) {
  const double twice_area = n < 3 ? 0 : TwiceSignedArea(v, n);
  if (!(twice_area > 2 * kSliverArea)) return;
  Piece p{verts.size(), verts.size() + n, v[0].x, v[0].y, v[0].x, v[0].y, 0.5 * twice_area};
  for (size_t i = 0; i < n; ++i) {
    p.min_x = std::min(p.min_x, v[i].x), p.max_x = std::max(p.max_x, v[i].x);
    p.min_y = std::min(p.min_y, v[i].y), p.max_y = std::max(p.max_y, v[i].y);
  }
  verts.insert(verts.end(), v, v + n);
  pieces.push_back(p);
}

double VisibleFootprint::Area() const {
  double area = 0;
  for (const Piece& p : pieces_) area += p.area;
  return area;
}

void VisibleFootprint::Start(std::span<const Vec2> outline) {
  pieces_.clear();
  verts_.clear();
  AddPiece(pieces_, verts_, outline.data(), outline.size());
}

bool VisibleFootprint::Subtract(const ScreenPolygon& occluder) {
  next_pieces_.clear();
  next_verts_.clear();
  const size_t edges = occluder.vertices.size();
  for (const Piece& piece : pieces_) {
    if (piece.max_x <= occluder.min_x || piece.min_x >= occluder.max_x ||
        piece.max_y <= occluder.min_y || piece.min_y >= occluder.max_y) {
      AddPiece(next_pieces_, next_verts_, verts_.data() + piece.begin, piece.end - piece.begin);
      continue;
    }
    // What is left of the piece inside the occluder's edges so far; what lies outside an edge is
    // visible, a piece of its own.
    const size_t capacity = 2 * (piece.end - piece.begin + edges) + 4;
    a_.resize(capacity), b_.resize(capacity), c_.resize(capacity);
    std::copy(verts_.begin() + piece.begin, verts_.begin() + piece.end, a_.begin());
    size_t n = piece.end - piece.begin;
    for (size_t i = 0; i < edges && n >= 3; ++i) {
      const ScreenLinear e = occluder.Edge(i);
      bool any_out = false, any_in = false;
      for (size_t k = 0; k < n; ++k) {
        const double v = e.At(a_[k].x, a_[k].y);
        any_out = any_out || v < 0;
        any_in = any_in || v > 0;
      }
      if (!any_out) continue;
      if (!any_in) {  // wholly outside this edge: visible
        AddPiece(next_pieces_, next_verts_, a_.data(), n);
        n = 0;
        break;
      }
      size_t in = 0, out = 0;
      if (!SplitByLine(a_.data(), n, e.a, e.b, e.c, b_.data(), in, c_.data(), out, capacity))
        return false;
      AddPiece(next_pieces_, next_verts_, c_.data(), out);
      std::swap(a_, b_);
      n = in;
    }
    if (next_pieces_.size() > kMaxPieces) return false;
  }
  if (next_pieces_.size() > kMaxPieces) return false;
  std::swap(pieces_, next_pieces_);
  std::swap(verts_, next_verts_);
  return true;
}

void VisibleFootprint::InRow(double x0, double cy, int cells, bool with_moments, CellMoments* out) {
  std::fill(out, out + cells, CellMoments{});
  const double y0 = cy - 0.5, y1 = cy + 0.5;
  for (const Piece& piece : pieces_) {
    if (piece.max_y <= y0 || piece.min_y >= y1 || piece.max_x <= x0 || piece.min_x >= x0 + cells)
      continue;
    // In the row's coordinates: x from its left side, y from its centre line.
    const size_t count = piece.end - piece.begin;
    const size_t capacity = 2 * count + 8;
    a_.resize(capacity), b_.resize(capacity), c_.resize(capacity);
    for (size_t k = 0; k < count; ++k) {
      const Vec2& v = verts_[piece.begin + k];
      a_[k] = {v.x - x0, v.y - cy};
    }
    size_t n = count;
    if (piece.min_y < y0) n = Clip(n, 0, 1, 0.5, capacity);
    if (n >= 3 && piece.max_y > y1) n = Clip(n, 0, -1, 0.5, capacity);
    if (n < 3) continue;
    const int first = std::max(0, static_cast<int>(std::floor(piece.min_x - x0)));
    const int last = std::min(cells - 1, static_cast<int>(std::ceil(piece.max_x - x0)) - 1);
    for (int i = first; i <= last && n >= 3; ++i) {
      // What lies left of the cell's right side is the cell's (the piece starts at or right of
      // the cell's left side); the rest goes on to the next cell.
      size_t in = n, rest = 0;
      Vec2* part = a_.data();
      if (i < last) {
        if (!SplitByLine(a_.data(), n, -1, 0, i + 1, b_.data(), in, c_.data(), rest, capacity))
          break;  // (not for a convex piece: its vertices at most double)
        part = b_.data();
      }
      if (in >= 3) {
        CellMoments m = PolygonMoments(std::span(part, in), with_moments);
        // From the row's origin to the cell's centre: x shifts by i + 0.5.
        const double c = i + 0.5;
        m.mxy -= c * m.my;
        m.mx -= c * m.area;
        Accumulate(out[i], m);
      }
      if (i < last) {
        std::swap(a_, c_);
        n = rest;
      }
    }
  }
}

namespace {

// Adds to row-major `cells` (`stride` per row, rows [0, rows)) the signed area between the edge
// (x0, y0) -> (x1, y1) and the line x = +inf, row by row and cell by cell: +dy for the cells right
// of the edge within its rows, the trapezoid's share in the cells it crosses. Coordinates are in
// cells; the edge lies inside x in [0, stride - 2], y in [0, rows].
void AccumulateEdge(double x0, double y0, double x1, double y1, int rows, int stride,
                    double* cells) {
  if (y0 == y1) return;
  const double dir = y0 < y1 ? 1.0 : -1.0;
  if (y0 > y1) std::swap(x0, x1), std::swap(y0, y1);
  const double dxdy = (x1 - x0) / (y1 - y0);
  const int first_row = std::max(0, static_cast<int>(std::floor(y0)));
  const int end_row = std::min(rows, static_cast<int>(std::ceil(y1)));
  for (int row = first_row; row < end_row; ++row) {
    const double top = std::max(y0, static_cast<double>(row));
    const double bottom = std::min(y1, static_cast<double>(row + 1));
    if (!(bottom > top)) continue;
    const double xa = x0 + dxdy * (top - y0), xb = x0 + dxdy * (bottom - y0);
    const double d = dir * (bottom - top);
    const double lo = std::min(xa, xb), hi = std::max(xa, xb);
    double* line = cells + static_cast<size_t>(row) * stride;
    const int i0 = static_cast<int>(std::floor(lo));
    const int i1 = static_cast<int>(std::floor(hi));
    if (i0 == i1 || (hi == std::floor(hi) && i1 == i0 + 1)) {
      // Within one cell: its part right of the edge's mean abscissa, the rest to the next.
      const double right = (i0 + 1) - 0.5 * (lo + hi);
      line[i0] += d * right;
      line[i0 + 1] += d * (1 - right);
      continue;
    }
    // Across cells i0 .. i1: the edge's height in each cell is in proportion to its width there;
    // each cell it crosses gets the part right of the edge, the cells after it the whole height.
    const double slope = d / (hi - lo);  // height per unit of x, signed
    double x = lo;
    for (int i = i0; i <= i1; ++i) {
      const double next = std::min(hi, static_cast<double>(i + 1));
      const double h = slope * (next - x);  // the edge's height inside cell i
      const double right = (i + 1) - 0.5 * (x + next);
      line[i] += h * right;
      line[i + 1] += h * (1 - right);
      x = next;
    }
  }
}

}  // namespace

void VisibleFootprint::AreasInCells(double x0, double y0, int columns, int rows, double* out) {
  const int stride = columns + 2;
  accumulated_.assign(static_cast<size_t>(stride) * rows, 0.0);
  for (const Piece& piece : pieces_) {
    const size_t n = piece.end - piece.begin;
    for (size_t k = 0; k < n; ++k) {
      const Vec2& p = verts_[piece.begin + k];
      const Vec2& q = verts_[piece.begin + (k + 1 == n ? 0 : k + 1)];
      AccumulateEdge(p.x - x0, p.y - y0, q.x - x0, q.y - y0, rows, stride, accumulated_.data());
    }
  }
  // Counter-clockwise on the screen (y down), the pieces' edges go up on their left: the sums
  // are negative inside.
  for (int row = 0; row < rows; ++row) {
    const double* line = accumulated_.data() + static_cast<size_t>(row) * stride;
    double sum = 0;
    for (int i = 0; i < columns; ++i) {
      sum += line[i];
      out[static_cast<size_t>(row) * columns + i] = -sum;
    }
  }
}

size_t VisibleFootprint::Clip(size_t n, double a, double b, double c, size_t capacity) {
  const size_t cut = ClipByHalfPlane(a_.data(), n, a, b, c, b_.data(), capacity);
  if (cut == kClipOverflow) return 0;  // (not for a convex piece: its vertices at most double)
  std::swap(a_, b_);
  return cut;
}

}  // namespace aperture
