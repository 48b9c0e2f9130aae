#include "render/visible_footprint.h"

#include <algorithm>
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
  if (n < 3 || !(TwiceSignedArea(v, n) > 2 * kSliverArea)) return;
  Piece p{verts.size(), verts.size() + n, v[0].x, v[0].y, v[0].x, v[0].y};
  for (size_t i = 0; i < n; ++i) {
    p.min_x = std::min(p.min_x, v[i].x), p.max_x = std::max(p.max_x, v[i].x);
    p.min_y = std::min(p.min_y, v[i].y), p.max_y = std::max(p.max_y, v[i].y);
  }
  verts.insert(verts.end(), v, v + n);
  pieces.push_back(p);
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

CellMoments VisibleFootprint::InCell(double cx, double cy, bool with_moments) {
  CellMoments sum;
  const double x0 = cx - 0.5, x1 = cx + 0.5, y0 = cy - 0.5, y1 = cy + 0.5;
  for (const Piece& piece : pieces_) {
    if (piece.max_x <= x0 || piece.min_x >= x1 || piece.max_y <= y0 || piece.min_y >= y1) continue;
    const size_t count = piece.end - piece.begin;
    const size_t capacity = 2 * count + 8;
    a_.resize(capacity), b_.resize(capacity);
    for (size_t k = 0; k < count; ++k) {
      const Vec2& v = verts_[piece.begin + k];
      a_[k] = {v.x - cx, v.y - cy};
    }
    size_t n = count;
    // Only the cell's sides that cross the piece cut it.
    const double cuts[4][3] = {{1, 0, 0.5}, {-1, 0, 0.5}, {0, 1, 0.5}, {0, -1, 0.5}};
    const bool crosses[4] = {piece.min_x<x0, piece.max_x> x1, piece.min_y<y0, piece.max_y> y1};
    for (int s = 0; s < 4 && n >= 3; ++s) {
      if (!crosses[s]) continue;
      const size_t cut =
          ClipByHalfPlane(a_.data(), n, cuts[s][0], cuts[s][1], cuts[s][2], b_.data(), capacity);
      if (cut == kClipOverflow) {  // (rounding past convexity: clip in vectors instead)
        a_.assign(verts_.begin() + piece.begin, verts_.begin() + piece.end);
        for (Vec2& v : a_) v = {v.x - cx, v.y - cy};
        ClipToRect(a_, -0.5, -0.5, 0.5, 0.5, b_);
        n = a_.size();
        break;
      }
      n = cut;
      std::swap(a_, b_);
    }
    if (n >= 3) Accumulate(sum, PolygonMoments(std::span(a_.data(), n), with_moments));
  }
  return sum;
}

}  // namespace aperture
