// Exact visible-area integrals in one unit cell of the screen: which parts of the polygons that
// overlap the cell are visible, with their areas and first moments (for seed 002's eq. 2).
//
// Visibility inside the cell is resolved exactly by a trapezoid decomposition: the cell is cut
// into horizontal slabs at every vertex, every edge crossing and every line where two polygons'
// depths are equal (the intersection line of interpenetrating polygons), and each slab into
// trapezoids between consecutive edges. Inside a trapezoid the set of covering polygons and their
// depth order are constant, so the front polygon is found at its centre and receives the
// trapezoid's exact area and moments. Interpenetrating polygons are therefore exact as well.
//
// Polygons whose depth ranges over the cell are stacked (small flat triangles drawn over one
// another, paint over the ground) skip the pieces, the pairwise tests and the decomposition: the
// painter cuts the cell's square by their crossing edges directly, nearest first (PaintStacked).
// Coplanar polygons (decals) are ordered by the scene's rule (raster/depth_order.h): a stack of
// planes, each holding any number of overlapping polygons, has one painter's order found by sorts.
//
// A crowded cell (more than kCrowdedPieces pieces: a whole scene seen in one pixel, a far city)
// is first cut into quadrants, recursively, each resolved with the pieces clipped to it, so its
// work grows with the pieces and their edges' length, not with their square or cube. The painter's
// remaining regions are bounded by the pieces' count: a square whose painting would fragment
// them further is cut into quadrants instead. A cell's memory grows with its pieces, never with
// their square.
#pragma once

#include <cstdint>
#include <functional>
#include <span>
#include <utility>
#include <vector>

#include "absl/container/flat_hash_map.h"
#include "raster/aa_filter.h"
#include "raster/depth_order.h"
#include "raster/screen_polygon.h"

namespace aperture {

struct CellPiece {
  int polygon;  // index into the frame's polygons
  CellMoments moments;
};

class CellCoverage {
 public:
  // More pieces than this in a square: cut it into four quadrants (the painter's order and the
  // pairwise tests cost the square of the pieces).
  static constexpr size_t kCrowdedPieces = 64;
  // More interpenetrating pieces than this (no painter's order): quadrants rather than the
  // trapezoid decomposition, whose cost grows with the cube of the pieces.
  static constexpr size_t kDecomposePieces = 8;
  // More pieces than this whose order the sorts do not find (not stacked plane by plane): cut
  // into quadrants rather than tested pair by pair (the pairs' marks cost the square).
  static constexpr size_t kPairwisePieces = 64;
  // The painter's remaining regions of a square of n pieces: at most this many per piece (and a
  // few more). Past them the square is cut into quadrants, whose pieces cross fewer edges.
  static constexpr size_t kRegionsPerPiece = 8;
  static constexpr size_t kRegionsAtLeast = 64;
  // A region of the painter smaller than this share of its square is dropped, not kept: the
  // sliver that rounding leaves between two polygons sharing an edge (a mesh placed twice, a
  // decal's edge along the pavement's). Its area is below any pixel value's resolution.
  static constexpr double kSliverArea = 1e-12;
  // Quadrant levels below the cell at most (a square of 1/4096 pixel). A square still crowded
  // there (a point many pieces share) goes to the piece in front at its centre: an error of at
  // most 4^-12 of the cell's weight for each such square. A square whose four quadrants would
  // each keep all of its pieces (a stack no cut separates) is resolved whole, exactly.
  static constexpr int kMaxDepth = 12;

  // Asked while a crowded cell is cut into squares and between slabs of a decomposition: once it
  // returns true the cell's result is incomplete (the caller abandons the frame). May be empty.
  void SetStop(std::function<bool()> stop) { stop_ = std::move(stop); }
  // Whether the last Compute was cut short by the stop test.
  bool Stopped() const { return stopped_; }
  // The bytes its scratch buffers hold (for a frame's memory budget).
  size_t WorkingBytes() const;

  // Visible pieces in the cell [cx - 0.5, cx + 0.5] x [cy - 0.5, cy + 0.5]. `candidates` are
  // indices into `polygons`; pieces with zero visible area are omitted. Output is appended.
  void Compute(std::span<const ScreenPolygon> polygons, std::span<const int> candidates, double cx,
               double cy, bool with_moments, std::vector<CellPiece>& out) {
    Compute(polygons, candidates, {}, {}, cx, cy, with_moments, out);
  }
  // The same with `candidates` nearest first: sorted by NearestQuantum(nearest[polygon]) (the
  // polygon's largest inverse depth over its vertices) descending, ties drawn last first
  // (raster/depth_order.h); `draw_order[polygon]` is its DrawOrder. The scan stops at the first
  // candidate whose nearest point lies behind a polygon already found to cover the whole cell
  // (behind its farthest corner): that one and every later one are hidden wherever they are; it
  // skips a candidate coplanar with the cover and drawn under it. Under a crowded frame's front
  // layer most candidates are not tested at all. The polygons found are then taken in index order
  // (unless their depth ranges are stacked, whose one painter's order needs none), which is the
  // order the plain Compute takes ascending candidates in (a Warnock leaf's lists are ascending),
  // so the result differs from it only where a hidden polygon's zero area would have come out as
  // rounding.
  void Compute(std::span<const ScreenPolygon> polygons, std::span<const int> candidates,
               std::span<const double> nearest, std::span<const int64_t> draw_order, double cx,
               double cy, bool with_moments, std::vector<CellPiece>& out);

 private:
  // The square being resolved, in cell-local coordinates (the cell is [-0.5, 0.5]^2).
  struct Square {
    double x0, y0, x1, y1;
  };
  struct Piece {
    int polygon;
    bool full;           // covers the whole square
    ScreenLinear depth;  // inv_depth in cell-local coordinates
    int64_t order;       // DrawOrder: which of two coplanar pieces is drawn over the other
    size_t begin, end;   // vertex range in verts_
  };
  struct Segment {
    double x0, y0, x1, y1;  // y0 < y1
    int piece;              // -1: a depth-equality line (splits, does not toggle)
    double XAt(double y) const { return x0 + (x1 - x0) * ((y - y0) / (y1 - y0)); }
  };

  // Resolves pieces_ (clipped to square_) into `out`; may subdivide.
  // `splittable`: false for a square that cutting does not separate (resolved whole).
  void Resolve(int depth, bool splittable, bool with_moments, std::vector<CellPiece>& out);
  // `force`: cut even when every quadrant keeps every piece (the whole square's resolution would
  // cost too much).
  void Subdivide(int depth, bool force, bool with_moments, std::vector<CellPiece>& out);
  void FrontAtCentre(std::vector<CellPiece>& out);
  CellMoments SquareMoments() const;
  // Whether item `a` hides item `b` wherever they overlap in square_ (DepthSign at its corners).
  template <class Item>
  bool HidesOverSquare(const Item& a, const Item& b) const {
    int signs[4], k = 0;
    for (double y : {square_.y0, square_.y1})
      for (double x : {square_.x0, square_.x1})
        signs[k++] = DepthSign(a.depth.At(x, y), b.depth.At(x, y));
    return HidesAt(signs, a.order > b.order);
  }
  // The item nearest at square_'s centre (coplanar ones: the one drawn over) among those that
  // `eligible` accepts, or -1.
  template <class Item, class Eligible>
  int NearestAtCentre(const std::vector<Item>& items, Eligible eligible) const {
    const double xc = 0.5 * (square_.x0 + square_.x1), yc = 0.5 * (square_.y0 + square_.y1);
    int front = -1;
    double best = 0;
    for (size_t i = 0; i < items.size(); ++i) {
      if (!eligible(items[i])) continue;
      const double w = items[i].depth.At(xc, yc);
      if (front >= 0) {
        const int s = DepthSign(w, best);
        if (s < 0 || (s == 0 && items[i].order < items[front].order)) continue;
      }
      front = static_cast<int>(i), best = w;
    }
    return front;
  }
  // The item that covers square_ whole and hides every other, or -1. Only the item nearest at the
  // centre can be it: a linear depth's value there is the corners' mean.
  template <class Item, class IsFull>
  int FrontHidingAll(const std::vector<Item>& items, IsFull is_full) const {
    const int front = NearestAtCentre(items, [](const Item&) { return true; });
    if (front < 0 || !is_full(items[front])) return -1;
    for (size_t i = 0; i < items.size(); ++i)
      if (static_cast<int>(i) != front && !HidesOverSquare(items[front], items[i])) return -1;
    return front;
  }
  // Drops the items that the full item nearest at square_'s centre hides (they have no visible
  // part), keeping the others in their order.
  template <class Item, class IsFull>
  [[gnu::noinline]] void DropHiddenByAFullOne(std::vector<Item>& items, IsFull is_full) const {
    const int hider = NearestAtCentre(items, is_full);
    if (hider < 0) return;
    const Item front = items[hider];  // a copy: items are compacted below
    size_t kept = 0;
    for (size_t i = 0; i < items.size(); ++i)
      if (static_cast<int>(i) == hider || !HidesOverSquare(front, items[i]))
        items[kept++] = items[i];
    items.resize(kept);
  }
  // Resolves reach_ when its polygons' depth ranges over the cell are stacked; else false.
  bool PaintStacked(std::span<const ScreenPolygon> polygons, double cx, double cy,
                    bool with_moments, std::vector<CellPiece>& out);
  // More polygons than this in a cell go the general way (the quadrants bound the painter's
  // regions of a crowded cell).
  static constexpr size_t kStackedPieces = 16;
  struct Reach;
  std::span<const Vec2> CutSquare(const Reach& r);
  [[gnu::noinline]] void SortReachByPolygon();  // a crowded cell's: kept out of Compute's loop
  CellMoments MomentsOf(const Piece& p, bool with_moments) const;
  bool Separated(const Piece& a, const Piece& b) const;
  // Every pair of pieces (but piece `skip`) has disjoint interiors.
  bool PairwiseDisjoint(size_t skip);
  void AddDepthEqualityLine(const Piece& a, const Piece& b);
  enum class Order { kFound, kInterpenetrating, kCyclic, kTooMany };
  // The painter's order into order_; `order_by_ranges`: pairs whose depth ranges do not meet are
  // ordered without a test.
  Order FrontToBackOrder(bool order_by_ranges);
  // order_ when the pieces' planes (each holding one or more coplanar pieces) are stacked in
  // depth over the pieces, found by sorting; else false.
  bool OrderByPlanes();
  // Each piece's inverse-depth range over its vertices, into nearest_ and farthest_.
  void DepthRanges();
  // False when the remaining regions would outgrow their bound (out is then left as it was).
  bool PaintFrontToBack(bool with_moments, std::vector<CellPiece>& out);
  // The painter's remaining regions: the whole square to begin with.
  void StartPainting();
  // Cuts the remaining regions that meet `box` by `lines` (a convex piece's inner half-planes,
  // a x + b y + c >= 0): returns the moments of what lies inside all of them, and with
  // `keep_rest` leaves the rest as the remaining regions (else they are left undefined).
  struct Box {
    double x0, y0, x1, y1;
  };
  // With `keep_rest`, fails (returns false, the regions then undefined) when more than
  // `max_regions` would remain.
  bool PaintInside(std::span<const ScreenLinear> lines, const Box& box, bool with_moments,
                   bool keep_rest, size_t max_regions, CellMoments& visible);
  void Decompose(bool with_moments, std::vector<CellPiece>& out);

  // A polygon reaching the cell, before clipping: its crossing edges are
  // crossing_[edges_begin, edges_end) (none: it covers the cell).
  struct Reach {
    int polygon;
    ScreenLinear depth;
    int64_t order;
    size_t edges_begin, edges_end;
  };
  std::vector<Reach> reach_;
  std::vector<Box> boxes_;                 // PairwiseDisjoint's sweep
  static constexpr size_t kFewPieces = 8;  // PairwiseDisjoint compares every pair's boxes
  std::vector<size_t> by_left_;
  std::vector<Piece> pieces_;
  std::vector<Vec2> verts_, clip_, scratch_;
  static constexpr size_t kClipBuffer = 64;
  Vec2 clip_buffers_[3][kClipBuffer];  // a piece being cut to the cell, a region being painted
  std::vector<ScreenLinear> crossing_;
  std::vector<ScreenLinear> lines_;  // the painted piece's edges that cut the square
  std::vector<uint8_t> in_front_;
  std::vector<size_t> blockers_;
  std::vector<double> nearest_, farthest_;  // each piece's inverse-depth range over itself
  std::vector<size_t> order_;
  struct Plane {
    size_t first;              // its pieces are planes_order_[first, next plane's first)
    double nearest, farthest;  // over its pieces' vertices
  };
  std::vector<size_t> planes_order_;
  std::vector<Plane> planes_;
  std::vector<size_t> plane_rank_;
  std::vector<Vec2> pool_a_, pool_b_, outside_;  // painter's remaining regions, flat
  std::vector<std::pair<size_t, size_t>> regions_a_,
      regions_b_;  // edges of one polygon that cross the cell, cell-local
  std::vector<Segment> segments_;
  std::vector<double> breaks_;
  std::vector<CellMoments> sums_;
  std::vector<uint8_t> inside_;
  struct Active {
    double xa, xb, xm;
    int piece;
  };
  std::vector<Active> active_;
  Square square_{-0.5, -0.5, 0.5, 0.5};
  bool subdivided_ = false;
  std::function<bool()> stop_;
  bool stopped_ = false;
  bool StopNow() {
    if (!stopped_ && stop_ && stop_()) stopped_ = true;
    return stopped_;
  }
  std::vector<CellPiece> crowded_out_;       // a subdivided cell's pieces before merging
  absl::flat_hash_map<int, size_t> merged_;  // polygon -> its piece in the output
};

}  // namespace aperture
