// The general path of a cell's exact coverage (raster/cell_coverage.h): pieces that are neither
// alone, nor hidden by one whole-cell cover, nor stacked polygon by polygon. Their painter's order
// by depth ranges, planes of coplanar pieces or pairwise tests, the painter (cell_coverage.cc),
// the trapezoid decomposition of a few interpenetrating pieces, and the quadrants of a crowded or
// fragmenting square. Kept apart from the per-cell scan, which every cell of a frame runs.
#include <algorithm>
#include <cmath>

#include "raster/cell_coverage.h"  // the class whose general path this is
#include "raster/polygon_clip.h"
#include "raster/polygon_moments.h"

namespace aperture {
namespace {

constexpr double kEps = 1e-12;

// Clips the segment p + t (q - p), t in [t0, t1], to a x + b y + c >= 0.
bool ClipParam(const Vec2& p, const Vec2& q, double a, double b, double c, double& t0, double& t1) {
  const double dp = a * p.x + b * p.y + c;
  const double dq = a * q.x + b * q.y + c;
  if (dp < 0 && dq < 0) return false;
  if (dp >= 0 && dq >= 0) return true;
  const double t = dp / (dp - dq);
  if (dp < 0)
    t0 = std::max(t0, t);
  else
    t1 = std::min(t1, t);
  return t0 < t1;
}

}  // namespace

void CellCoverage::Resolve(int depth, bool splittable, bool with_moments,
                           std::vector<CellPiece>& out) {
  if (pieces_.empty()) return;
  if (pieces_.size() == 1) {
    const CellMoments m = MomentsOf(pieces_[0], with_moments);
    if (m.area > 0) out.push_back({pieces_[0].polygon, m});
    return;
  }

  if (const int front = FrontHidingAll(pieces_, [](const Piece& p) { return p.full; });
      front >= 0) {
    out.push_back({pieces_[front].polygon, SquareMoments()});
    return;
  }
  // A quadrant's full pieces hide much of a crowded square's rest (coplanar layers under the
  // one drawn last, a stack under its front plane).
  if (depth > 0) DropHiddenByAFullOne(pieces_, [](const Piece& p) { return p.full; });

  const bool may_split = depth < kMaxDepth;
  // A crowd of pieces on a few planes (layers of decals): painted in the planes' order, whose
  // regions stay few under the front layers, rather than cut into quadrants piece by piece.
  if (pieces_.size() > kCrowdedPieces && splittable) {
    DepthRanges();
    if (OrderByPlanes() && PaintFrontToBack(with_moments, out)) return;
  }
  if (pieces_.size() > kCrowdedPieces && splittable) {
    if (may_split) {
      Subdivide(depth, /*force=*/false, with_moments, out);
    } else
      FrontAtCentre(out);
    return;
  }

  // Layers: a full piece behind all others over the whole square (ground under runway paint,
  // under a building's edge), the others disjoint: each front piece keeps its own moments and
  // the background gets the rest of the square.
  bool overlapping = false;
  for (size_t b = 0; b < pieces_.size(); ++b) {
    const Piece& back = pieces_[b];
    if (!back.full) continue;
    // Depth differences are linear, so a piece is in front over all of itself when it is at its
    // vertices; touching (a wall standing on the ground) counts as in front, and a piece coplanar
    // with the background is in front when it is drawn over it.
    bool behind = true;
    for (size_t q = 0; q < pieces_.size() && behind; ++q) {
      if (q == b) continue;
      bool nearer = false;
      for (size_t k = pieces_[q].begin; k < pieces_[q].end && behind; ++k) {
        const Vec2& v = verts_[k];
        const int sign = DepthSign(pieces_[q].depth.At(v.x, v.y), back.depth.At(v.x, v.y));
        behind = sign >= 0;
        nearer = nearer || sign > 0;
      }
      behind = behind && (nearer || pieces_[q].order > back.order);
    }
    if (!behind) break;
    if (!PairwiseDisjoint(b)) {
      overlapping = true;  // two pieces besides the background overlap
      break;
    }
    CellMoments rest = SquareMoments();
    for (size_t q = 0; q < pieces_.size(); ++q) {
      if (q == b) continue;
      const CellMoments m = MomentsOf(pieces_[q], with_moments);
      if (m.area > 0) out.push_back({pieces_[q].polygon, m});
      rest = {rest.area - m.area, rest.mx - m.mx, rest.my - m.my, rest.mxy - m.mxy};
    }
    if (rest.area > 0) out.push_back({back.polygon, rest});
    return;
  }

  // Pieces whose interiors are disjoint (neighbours in a mesh) need no visibility at all.
  if (!overlapping && PairwiseDisjoint(pieces_.size())) {
    for (const Piece& p : pieces_) {
      const CellMoments m = MomentsOf(p, with_moments);
      if (m.area > 0) out.push_back({p.polygon, m});
    }
    return;
  }
  // The depth-range shortcut also orders pieces that never overlap, which can close a cycle that
  // the pieces do not really have: then the order is sought again with every pair tested.
  Order order = FrontToBackOrder(/*order_by_ranges=*/true);
  if (order == Order::kCyclic) order = FrontToBackOrder(/*order_by_ranges=*/false);
  if (order == Order::kFound && PaintFrontToBack(with_moments, out)) return;
  // Interpenetrating pieces with no painter's order: the trapezoid decomposition, which costs
  // about the cube of the pieces, for a handful. More of them, too many to order, or a painting
  // whose regions would outgrow their bound: quadrants, whose pieces cross fewer edges and are
  // more often full.
  const bool no_order = order == Order::kInterpenetrating || order == Order::kCyclic;
  if (no_order && pieces_.size() <= kDecomposePieces) {
    Decompose(with_moments, out);
    return;
  }
  if (may_split) {
    Subdivide(depth, /*force=*/true, with_moments, out);
    return;
  }
  FrontAtCentre(out);
}

// The square's four quadrants, each with the pieces clipped to it. A piece is full in a quadrant
// when the quadrant's corners are inside it (then its vertices are the quadrant's). When every
// quadrant keeps all of the square's pieces (pieces stacked over the whole square, which no cut
// separates), the square is resolved whole instead; a quadrant that alone keeps them all (a vertex
// many pieces share) is cut on, down to kMaxDepth.
void CellCoverage::Subdivide(int depth, bool force, bool with_moments,
                             std::vector<CellPiece>& out) {
  subdivided_ = true;
  if (StopNow()) return;
  const Square whole = square_;
  std::vector<Piece> parent = std::move(pieces_);
  std::vector<Vec2> parent_verts = std::move(verts_);
  const double xm = 0.5 * (whole.x0 + whole.x1), ym = 0.5 * (whole.y0 + whole.y1);
  const Square quadrants[4] = {{whole.x0, whole.y0, xm, ym},
                               {xm, whole.y0, whole.x1, ym},
                               {whole.x0, ym, xm, whole.y1},
                               {xm, ym, whole.x1, whole.y1}};
  std::vector<Piece> child_pieces[4];
  std::vector<Vec2> child_verts[4];
  bool all_kept = true;
  for (int c = 0; c < 4; ++c) {
    const Square& q = quadrants[c];
    std::vector<Piece>& pieces = child_pieces[c];
    std::vector<Vec2>& verts = child_verts[c];
    const Vec2 corners[4] = {{q.x0, q.y0}, {q.x1, q.y0}, {q.x1, q.y1}, {q.x0, q.y1}};
    for (const Piece& p : parent) {
      const std::span<const Vec2> pv(parent_verts.data() + p.begin, p.end - p.begin);
      Piece sub = p;
      sub.begin = verts.size();
      if (p.full) {
        verts.insert(verts.end(), std::begin(corners), std::end(corners));
      } else {
        double x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY;
        for (const Vec2& v : pv) {
          x0 = std::min(x0, v.x), x1 = std::max(x1, v.x);
          y0 = std::min(y0, v.y), y1 = std::max(y1, v.y);
        }
        if (x1 <= q.x0 || x0 >= q.x1 || y1 <= q.y0 || y0 >= q.y1) continue;  // beside it
        if (x0 >= q.x0 && x1 <= q.x1 && y0 >= q.y0 && y1 <= q.y1) {
          verts.insert(verts.end(), pv.begin(), pv.end());  // wholly inside: no cut
        } else {
          // Full when every corner is inside every edge (touching counts).
          sub.full = x0 <= q.x0 && x1 >= q.x1 && y0 <= q.y0 && y1 >= q.y1;
          for (size_t i = 0; i < pv.size() && sub.full; ++i) {
            const Vec2& a = pv[i];
            const Vec2& b = pv[i + 1 == pv.size() ? 0 : i + 1];
            for (const Vec2& k : corners)
              sub.full = sub.full && (b.x - a.x) * (k.y - a.y) - (b.y - a.y) * (k.x - a.x) >= 0;
          }
          if (sub.full) {
            verts.insert(verts.end(), std::begin(corners), std::end(corners));
          } else {
            clip_.assign(pv.begin(), pv.end());
            // Only the quadrant's sides that cut the piece's box.
            if (x0 < q.x0) ClipByHalfPlane(clip_, 1, 0, -q.x0, scratch_);
            if (x1 > q.x1 && !clip_.empty()) ClipByHalfPlane(clip_, -1, 0, q.x1, scratch_);
            if (y0 < q.y0 && !clip_.empty()) ClipByHalfPlane(clip_, 0, 1, -q.y0, scratch_);
            if (y1 > q.y1 && !clip_.empty()) ClipByHalfPlane(clip_, 0, -1, q.y1, scratch_);
            if (clip_.size() < 3 || !(PolygonMoments(clip_, false).area > 0)) continue;
            verts.insert(verts.end(), clip_.begin(), clip_.end());
          }
        }
      }
      sub.end = verts.size();
      pieces.push_back(sub);
    }
    all_kept = all_kept && pieces.size() == parent.size();
  }
  if (all_kept && !force) {
    pieces_ = std::move(parent);
    verts_ = std::move(parent_verts);
    Resolve(depth, /*splittable=*/false, with_moments, out);
    return;
  }
  for (int c = 0; c < 4; ++c) {
    pieces_ = std::move(child_pieces[c]);
    verts_ = std::move(child_verts[c]);
    square_ = quadrants[c];
    Resolve(depth + 1, /*splittable=*/true, with_moments, out);
  }
  square_ = whole;
}

// At kMaxDepth a square still too crowded to resolve (a point many pieces share, edges crossing
// every way) goes whole to the piece in front at its centre: an error of at most 4^-kMaxDepth of
// the cell each.
void CellCoverage::FrontAtCentre(std::vector<CellPiece>& out) {
  const double xc = 0.5 * (square_.x0 + square_.x1), yc = 0.5 * (square_.y0 + square_.y1);
  int front = -1;
  double best = 0;
  int64_t best_order = 0;
  for (const Piece& p : pieces_) {
    bool inside = true;
    const size_t n = p.end - p.begin;
    for (size_t i = 0; i < n && inside && !p.full; ++i) {
      const Vec2& a = verts_[p.begin + i];
      const Vec2& b = verts_[p.begin + (i + 1 == n ? 0 : i + 1)];
      inside = (b.x - a.x) * (yc - a.y) - (b.y - a.y) * (xc - a.x) >= 0;
    }
    if (!inside) continue;
    const double w = p.depth.At(xc, yc);
    const int sign = front < 0 ? 1 : DepthSign(w, best);
    if (sign > 0 || (sign == 0 && p.order > best_order))
      front = p.polygon, best = w, best_order = p.order;
  }
  if (front >= 0) out.push_back({front, SquareMoments()});
}

// Pieces that overlap must not interpenetrate: their depth difference, linear, keeps one sign
// at the vertices of both (hence over their convex hull, hence where they overlap). A pair whose
// depth ranges (each over its own vertices, depth being linear) do not meet needs no test at all:
// the nearer one is in front wherever they overlap. Then a topological sort of "in front of"
// (Kahn's, by counting the pieces still in front of each) gives the painter's order, unless the
// order is cyclic.
void CellCoverage::DepthRanges() {
  const size_t n = pieces_.size();
  nearest_.resize(n);
  farthest_.resize(n);
  for (size_t i = 0; i < n; ++i) {
    const Piece& p = pieces_[i];
    double lo = INFINITY, hi = -INFINITY;
    for (size_t k = p.begin; k < p.end; ++k) {
      const double w = p.depth.At(verts_[k].x, verts_[k].y);
      lo = std::min(lo, w);
      hi = std::max(hi, w);
    }
    farthest_[i] = lo;  // inverse depth: larger is nearer
    nearest_[i] = hi;
  }
}

CellCoverage::Order CellCoverage::FrontToBackOrder(bool order_by_ranges) {
  const size_t n = pieces_.size();
  DepthRanges();
  if (order_by_ranges) {
    // Depth ranges that, nearest first, each lie wholly in front of the next order every pair
    // by the ranges alone: that order is the only painter's order (the one the pairwise marks and
    // Kahn's sort below would find), in k log k rather than k^2 (a crowded cell of a far city).
    order_.resize(n);
    for (size_t i = 0; i < n; ++i) order_[i] = i;
    std::sort(order_.begin(), order_.end(), [&](size_t a, size_t b) {
      return nearest_[a] > nearest_[b] || (nearest_[a] == nearest_[b] && a < b);
    });
    bool stacked = true;
    for (size_t k = 0; k + 1 < n && stacked; ++k)
      stacked = DepthSign(farthest_[order_[k]], nearest_[order_[k + 1]]) > 0;
    if (stacked) return Order::kFound;
    if (OrderByPlanes()) return Order::kFound;
  }
  if (n > kPairwisePieces) return Order::kTooMany;
  in_front_.assign(n * n, 0);  // in_front_[i * n + j]: i is in front of j
  blockers_.assign(n, 0);      // how many pieces are in front of each
  auto mark = [&](size_t front, size_t back) {
    in_front_[front * n + back] = 1;
    ++blockers_[back];
  };
  for (size_t i = 0; i < n; ++i) {
    for (size_t j = i + 1; j < n; ++j) {
      if (order_by_ranges && DepthSign(farthest_[i], nearest_[j]) > 0) {
        mark(i, j);
        continue;
      }
      if (order_by_ranges && DepthSign(farthest_[j], nearest_[i]) > 0) {
        mark(j, i);
        continue;
      }
      if (Separated(pieces_[i], pieces_[j])) continue;
      bool i_front = true, j_front = true;
      for (const Piece* piece : {&pieces_[i], &pieces_[j]}) {
        for (size_t k = piece->begin; k < piece->end; ++k) {
          const Vec2& v = verts_[k];
          const int sign = DepthSign(pieces_[i].depth.At(v.x, v.y), pieces_[j].depth.At(v.x, v.y));
          i_front = i_front && sign >= 0;
          j_front = j_front && sign <= 0;
        }
      }
      if (!i_front && !j_front) return Order::kInterpenetrating;  // decompose
      // Coplanar (equal within the tolerance at every vertex): the one drawn over the other is
      // in front, as the decomposition and the front at a point decide a tie.
      if (i_front && j_front) i_front = pieces_[i].order > pieces_[j].order;
      if (i_front)
        mark(i, j);
      else
        mark(j, i);
    }
  }
  order_.clear();
  for (size_t i = 0; i < n; ++i)
    if (blockers_[i] == 0) order_.push_back(i);
  for (size_t next = 0; next < order_.size(); ++next) {
    const size_t front = order_[next];
    for (size_t j = 0; j < n; ++j)
      if (in_front_[front * n + j] && --blockers_[j] == 0) order_.push_back(j);
  }
  return order_.size() == n ? Order::kFound : Order::kCyclic;
}

// Pieces on a few planes, each plane holding any number of overlapping coplanar pieces (layers
// of decals, 27 polygons deep, or a stack of such layers a millimetre apart): the pieces sorted by
// their depth at the square's centre put each plane's pieces together; a plane's pieces go front
// to back by the order they are drawn in, and planes whose depth ranges (over their pieces) are
// stacked go nearest first. Two sorts, where the pairwise marks cost the square of the pieces.
bool CellCoverage::OrderByPlanes() {
  const size_t n = pieces_.size();
  const double xc = 0.5 * (square_.x0 + square_.x1), yc = 0.5 * (square_.y0 + square_.y1);
  planes_order_.resize(n);
  for (size_t i = 0; i < n; ++i) planes_order_[i] = i;
  std::sort(planes_order_.begin(), planes_order_.end(), [&](size_t a, size_t b) {
    const double wa = pieces_[a].depth.At(xc, yc), wb = pieces_[b].depth.At(xc, yc);
    return wa > wb || (wa == wb && a < b);
  });
  // Planes: runs of pieces equal within the tolerance, at the square's corners, to the run's first.
  planes_.clear();
  plane_rank_.resize(n);
  for (size_t k = 0; k < n; ++k) {
    const Piece& piece = pieces_[planes_order_[k]];
    bool same = !planes_.empty();
    if (same) {
      const Piece& first = pieces_[planes_order_[planes_.back().first]];
      for (double y : {square_.y0, square_.y1})
        for (double x : {square_.x0, square_.x1})
          same = same && DepthSign(piece.depth.At(x, y), first.depth.At(x, y)) == 0;
    }
    if (!same) planes_.push_back({k, -INFINITY, INFINITY});
    Plane& plane = planes_.back();
    plane.nearest = std::max(plane.nearest, nearest_[planes_order_[k]]);
    plane.farthest = std::min(plane.farthest, farthest_[planes_order_[k]]);
    plane_rank_[planes_order_[k]] = planes_.size() - 1;
  }
  if (planes_.size() == n) return false;  // no two coplanar: the ranges' order already failed
  // The planes nearest first by their ranges, each wholly in front of the next.
  std::vector<Plane>& planes = planes_;
  order_.resize(planes.size());
  for (size_t g = 0; g < planes.size(); ++g) order_[g] = g;
  std::sort(order_.begin(), order_.end(),
            [&](size_t a, size_t b) { return planes[a].nearest > planes[b].nearest; });
  for (size_t k = 0; k + 1 < order_.size(); ++k)
    if (DepthSign(planes[order_[k]].farthest, planes[order_[k + 1]].nearest) <= 0) return false;
  // Each plane's rank in depth, then the pieces by that rank and, within a plane, the one drawn
  // last first.
  std::vector<size_t>& depth_rank = blockers_;
  depth_rank.resize(planes.size());
  for (size_t k = 0; k < order_.size(); ++k) depth_rank[order_[k]] = k;
  order_.resize(n);
  for (size_t i = 0; i < n; ++i) order_[i] = i;
  std::sort(order_.begin(), order_.end(), [&](size_t a, size_t b) {
    const size_t ra = depth_rank[plane_rank_[a]], rb = depth_rank[plane_rank_[b]];
    return ra < rb || (ra == rb && pieces_[a].order > pieces_[b].order);
  });
  return true;
}

// Only pairs whose bounding boxes overlap are tested, so a mesh's pieces cost about k log k, not
// k^2: a sweep along x over the boxes sorted by their left side, or for a few pieces every pair's
// boxes compared (the same pairs, without the sort).
bool CellCoverage::PairwiseDisjoint(size_t skip) {
  const size_t n = pieces_.size();
  boxes_.resize(n);
  by_left_.clear();
  for (size_t i = 0; i < n; ++i) {
    const Piece& p = pieces_[i];
    Box b{INFINITY, INFINITY, -INFINITY, -INFINITY};
    for (size_t k = p.begin; k < p.end; ++k) {
      b.x0 = std::min(b.x0, verts_[k].x), b.x1 = std::max(b.x1, verts_[k].x);
      b.y0 = std::min(b.y0, verts_[k].y), b.y1 = std::max(b.y1, verts_[k].y);
    }
    boxes_[i] = b;
    if (i != skip) by_left_.push_back(i);
  }
  // Boxes a (left side first) and b overlap when b's left side is within a's x range and their
  // y ranges meet; touching counts.
  auto boxes_meet = [](const Box& a, const Box& b) {
    return b.x0 <= a.x1 && !(b.y1 < a.y0 || b.y0 > a.y1);
  };
  if (by_left_.size() <= kFewPieces) {
    for (size_t u = 0; u < by_left_.size(); ++u) {
      for (size_t v = u + 1; v < by_left_.size(); ++v) {
        const Box &a = boxes_[by_left_[u]], &b = boxes_[by_left_[v]];
        const bool meet = a.x0 <= b.x0 ? boxes_meet(a, b) : boxes_meet(b, a);
        if (meet && !Separated(pieces_[by_left_[u]], pieces_[by_left_[v]])) return false;
      }
    }
    return true;
  }
  std::sort(by_left_.begin(), by_left_.end(),
            [&](size_t a, size_t b) { return boxes_[a].x0 < boxes_[b].x0; });
  for (size_t u = 0; u < by_left_.size(); ++u) {
    const Box& a = boxes_[by_left_[u]];
    for (size_t v = u + 1; v < by_left_.size() && boxes_[by_left_[v]].x0 <= a.x1; ++v) {
      const Box& b = boxes_[by_left_[v]];
      if (b.y1 < a.y0 || b.y0 > a.y1) continue;
      if (!Separated(pieces_[by_left_[u]], pieces_[by_left_[v]])) return false;
    }
  }
  return true;
}

// Separating-axis test with the edges of both convex pieces; touching counts as separated.
bool CellCoverage::Separated(const Piece& a, const Piece& b) const {
  auto separates = [&](const Piece& edges, const Piece& other) {
    const size_t n = edges.end - edges.begin;
    for (size_t i = 0; i < n; ++i) {
      const Vec2& p = verts_[edges.begin + i];
      const Vec2& q = verts_[edges.begin + (i + 1 == n ? 0 : i + 1)];
      const double ex = q.x - p.x, ey = q.y - p.y;
      const double tol = kEps * (std::abs(ex) + std::abs(ey));
      if (tol == 0) continue;  // clipping can repeat a vertex: a zero-length edge separates nothing
      bool all_outside = true;
      for (size_t k = other.begin; k < other.end && all_outside; ++k) {
        const Vec2& v = verts_[k];
        all_outside = ex * (v.y - p.y) - ey * (v.x - p.x) <= tol;
      }
      if (all_outside) return true;
    }
    return false;
  };
  return separates(a, b) || separates(b, a);
}

// The line where two pieces' depths are equal, clipped to both pieces, becomes a splitting edge.
void CellCoverage::AddDepthEqualityLine(const Piece& a, const Piece& b) {
  const double da = a.depth.a - b.depth.a, db = a.depth.b - b.depth.b, dc = a.depth.c - b.depth.c;
  const double scale = std::abs(a.depth.a) + std::abs(a.depth.b) + std::abs(a.depth.c) +
                       std::abs(b.depth.a) + std::abs(b.depth.b) + std::abs(b.depth.c);
  if (std::abs(da) + std::abs(db) <= 1e-14 * scale) return;  // parallel planes never cross
  Vec2 p, q;
  const Square& s = square_;
  if (std::abs(da) >= std::abs(db)) {  // x = -(db y + dc) / da
    p = {-(db * s.y0 + dc) / da, s.y0};
    q = {-(db * s.y1 + dc) / da, s.y1};
  } else {  // y = -(da x + dc) / db
    p = {s.x0, -(da * s.x0 + dc) / db};
    q = {s.x1, -(da * s.x1 + dc) / db};
  }
  double t0 = 0, t1 = 1;
  for (const Piece* piece : {&a, &b}) {
    const size_t n = piece->end - piece->begin;
    for (size_t i = 0; i < n; ++i) {
      const Vec2& e0 = verts_[piece->begin + i];
      const Vec2& e1 = verts_[piece->begin + (i + 1 == n ? 0 : i + 1)];
      // Inside of a counter-clockwise edge: cross(e1 - e0, v - e0) >= 0.
      const double ea = -(e1.y - e0.y), eb = e1.x - e0.x;
      const double ec = -(ea * e0.x + eb * e0.y);
      if (!ClipParam(p, q, ea, eb, ec, t0, t1)) return;
    }
  }
  const Vec2 from{p.x + (q.x - p.x) * t0, p.y + (q.y - p.y) * t0};
  const Vec2 to{p.x + (q.x - p.x) * t1, p.y + (q.y - p.y) * t1};
  if (from.y == to.y) {
    breaks_.push_back(from.y);  // horizontal: a slab boundary is enough
  } else if (from.y < to.y) {
    segments_.push_back({from.x, from.y, to.x, to.y, -1});
  } else {
    segments_.push_back({to.x, to.y, from.x, from.y, -1});
  }
}

void CellCoverage::Decompose(bool with_moments, std::vector<CellPiece>& out) {
  segments_.clear();
  breaks_.assign({square_.y0, square_.y1});
  for (size_t pi = 0; pi < pieces_.size(); ++pi) {
    const Piece& p = pieces_[pi];
    const size_t n = p.end - p.begin;
    for (size_t i = 0; i < n; ++i) {
      const Vec2& a = verts_[p.begin + i];
      const Vec2& b = verts_[p.begin + (i + 1 == n ? 0 : i + 1)];
      breaks_.push_back(a.y);
      if (a.y == b.y) continue;
      if (a.y < b.y)
        segments_.push_back({a.x, a.y, b.x, b.y, static_cast<int>(pi)});
      else
        segments_.push_back({b.x, b.y, a.x, a.y, static_cast<int>(pi)});
    }
  }
  for (size_t i = 0; i < pieces_.size(); ++i)
    for (size_t j = i + 1; j < pieces_.size(); ++j)
      if (!Separated(pieces_[i], pieces_[j])) AddDepthEqualityLine(pieces_[i], pieces_[j]);
  for (const Segment& s : segments_)
    if (s.piece < 0) breaks_.push_back(s.y0), breaks_.push_back(s.y1);

  // Every crossing of two segments is a slab boundary, so no two edges cross inside a slab.
  for (size_t i = 0; i < segments_.size(); ++i) {
    const Segment& s = segments_[i];
    for (size_t j = i + 1; j < segments_.size(); ++j) {
      const Segment& t = segments_[j];
      if (s.piece >= 0 && s.piece == t.piece) continue;  // edges of one convex piece
      const double lo = std::max(s.y0, t.y0), hi = std::min(s.y1, t.y1);
      if (!(lo < hi)) continue;
      const double d_lo = s.XAt(lo) - t.XAt(lo), d_hi = s.XAt(hi) - t.XAt(hi);
      if ((d_lo < 0 && d_hi > 0) || (d_lo > 0 && d_hi < 0))
        breaks_.push_back(lo + (hi - lo) * (d_lo / (d_lo - d_hi)));
    }
  }
  std::sort(breaks_.begin(), breaks_.end());
  breaks_.erase(std::unique(breaks_.begin(), breaks_.end()), breaks_.end());

  sums_.assign(pieces_.size(), CellMoments{});
  inside_.assign(pieces_.size(), 0);
  for (size_t k = 0; k + 1 < breaks_.size(); ++k) {
    if (k % 64 == 63 && StopNow()) return;
    const double ya = std::max(breaks_[k], square_.y0), yb = std::min(breaks_[k + 1], square_.y1);
    if (!(ya < yb)) continue;
    const double ym = 0.5 * (ya + yb);
    active_.clear();
    for (const Segment& s : segments_) {
      if (!(s.y0 < ym && ym < s.y1)) continue;
      active_.push_back({s.XAt(ya), s.XAt(yb), s.XAt(ym), s.piece});
    }
    std::sort(active_.begin(), active_.end(),
              [](const Active& l, const Active& r) { return l.xm < r.xm; });
    std::fill(inside_.begin(), inside_.end(), 0);
    for (size_t i = 0; i + 1 < active_.size(); ++i) {
      if (active_[i].piece >= 0) inside_[active_[i].piece] ^= 1;
      const Active& l = active_[i];
      const Active& r = active_[i + 1];
      if (!(r.xa - l.xa + r.xb - l.xb > 0)) continue;
      const double xc = 0.25 * (l.xa + r.xa + l.xb + r.xb);
      int front = -1;
      double best = 0;
      for (size_t p = 0; p < pieces_.size(); ++p) {
        if (!inside_[p]) continue;
        const double d = pieces_[p].depth.At(xc, ym);
        const int sign = front < 0 ? 1 : DepthSign(d, best);
        if (sign > 0 || (sign == 0 && pieces_[p].order > pieces_[front].order))
          front = static_cast<int>(p), best = d;
      }
      if (front < 0) continue;
      const Vec2 trapezoid[4] = {{l.xa, ya}, {r.xa, ya}, {r.xb, yb}, {l.xb, yb}};
      Accumulate(sums_[front], PolygonMoments(trapezoid, with_moments));
    }
  }
  for (size_t p = 0; p < pieces_.size(); ++p)
    if (sums_[p].area > 0) out.push_back({pieces_[p].polygon, sums_[p]});
}

}  // namespace aperture
