#include "raster/cell_coverage.h"

#include <algorithm>
#include <cmath>

#include "base/held_bytes.h"
#include "raster/polygon_clip.h"
#include "raster/polygon_moments.h"

namespace aperture {
namespace {

constexpr double kHalf = 0.5;

// A region's few vertices, copied one by one: a call of memmove for each (what std::copy and
// vector::insert make of them) cost 4 % of a frame of 100,000 small triangles.
void CopyVertices(std::span<const Vec2> from, Vec2* to) {
#pragma GCC unroll 4
  for (size_t k = 0; k < from.size(); ++k) to[k] = from[k];
}

}  // namespace

void CellCoverage::Compute(std::span<const ScreenPolygon> polygons, std::span<const int> candidates,
                           std::span<const double> nearest, std::span<const int64_t> draw_order,
                           double cx, double cy, bool with_moments, std::vector<CellPiece>& out) {
  // First which polygons reach the cell and how (no clipping yet): a cell wholly covered by the
  // polygon in front of all the others is then answered without clipping any of them.
  stopped_ = false;
  reach_.clear();
  size_t crossings = 0;  // crossing_[0, crossings) are used
  // Nearest first: the farthest corner of the nearest whole-cell cover found, and the order it
  // is drawn in (of covers equally far within the tolerance, the one drawn last).
  double cover_far = -INFINITY;
  int64_t cover_order = 0;
  // Below `behind` a candidate's nearest point is behind the cover by a margin, and so is every
  // later candidate's (they come nearest first to within NearestQuantum's resolution, a quarter
  // of the margin); up to `tied` it is nowhere nearer than the cover beyond the tolerance.
  double behind = -INFINITY, tied = -INFINITY;
  for (int index : candidates) {
    if (!nearest.empty()) {
      const double w = nearest[index];
      if (w < behind) break;
      // A coplanar layer under the cover: hidden, skipped without a look at its edges.
      if (w <= tied && draw_order[index] < cover_order) continue;
    }
    const ScreenPolygon& sp = polygons[index];
    if (sp.max_x <= cx - kHalf || sp.min_x >= cx + kHalf || sp.max_y <= cy - kHalf ||
        sp.min_y >= cy + kHalf)
      continue;
    // Over the cell each edge function ranges over e(centre) +- r: the cell is outside the
    // polygon when one edge is negative all over it, inside when all are non-negative; only
    // the edges that cross the cell clip it. Branch-free: every edge is written and the count
    // advances past those that cross (which edges cross varies from cell to cell).
    const size_t edges = sp.vertices.size();
    if (crossing_.size() < crossings + edges) crossing_.resize(2 * (crossings + edges));
    bool outside = false;
    const size_t first_edge = crossings;
    for (size_t i = 0; i < edges; ++i) {
      const ScreenLinear e = sp.Edge(i);
      const double d = e.At(cx, cy), r = kHalf * (std::abs(e.a) + std::abs(e.b));
      outside |= d + r <= 0;
      crossing_[crossings] = {e.a, e.b, d};
      crossings += d - r < 0;
    }
    if (outside) {
      crossings = first_edge;
      continue;
    }
    reach_.push_back({index,
                      {sp.inv_depth.a, sp.inv_depth.b, sp.inv_depth.At(cx, cy)},
                      DrawOrder(sp.layer, index),
                      first_edge,
                      crossings});
    if (!nearest.empty() && first_edge == crossings) {  // covers the cell
      const ScreenLinear& d = reach_.back().depth;
      const double far = d.c - kHalf * (std::abs(d.a) + std::abs(d.b));
      const int sign = DepthSign(far, cover_far);
      if (cover_far == -INFINITY || sign > 0 || (sign == 0 && reach_.back().order > cover_order)) {
        cover_far = far, cover_order = reach_.back().order;
        const double tolerance = kCoplanarTolerance * std::abs(far);
        behind = far - 4 * tolerance;
        tied = far + 2 * tolerance;  // DepthSign's tie, |w| and |far| being alike there
      }
    }
  }
  if (reach_.empty()) return;
  square_ = {-kHalf, -kHalf, kHalf, kHalf};
  if (reach_.size() == 1) {  // one polygon (most cells of a sparse frame): as Resolve would do
    const Reach& r = reach_[0];
    if (!with_moments && r.edges_end - r.edges_begin == 1) {  // one edge: its area in closed form
      const ScreenLinear& e = crossing_[r.edges_begin];
      const double area = HalfPlaneCellArea(e.a, e.b, e.c);
      if (area > 0) out.push_back({r.polygon, {area, 0, 0, 0}});
      return;
    }
    const CellMoments m =
        r.edges_begin == r.edges_end ? SquareMoments() : PolygonMoments(CutSquare(r), with_moments);
    if (m.area > 0) out.push_back({r.polygon, m});
    return;
  }
  // Stacked polygons have one painter's order, whatever the order found: the whole-cell cover in
  // front of all (the test below) is then the first painted, and the polygons that
  // DropHiddenByAFullPolygon drops lie behind the first cover painted, where the painter stops.
  if (PaintStacked(polygons, cx, cy, with_moments, out)) return;
  if (!nearest.empty()) {  // back to the polygons' order (mostly few: an insertion sort)
    if (reach_.size() > kCrowdedPieces) {
      SortReachByPolygon();
    } else {
      for (size_t i = 1; i < reach_.size(); ++i)
        for (size_t j = i; j > 0 && reach_[j - 1].polygon > reach_[j].polygon; --j)
          std::swap(reach_[j - 1], reach_[j]);
    }
  }
  // The test Resolve makes first, on every polygon that reaches the cell: when it holds here it
  // holds for the clipped pieces too, which are these less the empty ones.
  if (const int front =
          FrontHidingAll(reach_, [](const Reach& r) { return r.edges_begin == r.edges_end; });
      front >= 0) {
    out.push_back({reach_[front].polygon, SquareMoments()});
    return;
  }
  // The full polygon nearest at the centre hides every polygon it hides at the four corners: those
  // have no visible part and are dropped before any clipping. Under a few near pieces a crowded
  // cell mostly holds such. What is left may be stacked.
  DropHiddenByAFullOne(reach_, [](const Reach& r) { return r.edges_begin == r.edges_end; });
  if (PaintStacked(polygons, cx, cy, with_moments, out)) return;
  pieces_.clear();
  verts_.clear();
  for (const Reach& r : reach_) {
    Piece piece;
    piece.polygon = r.polygon;
    piece.depth = r.depth;
    piece.order = r.order;
    piece.full = r.edges_begin == r.edges_end;
    piece.begin = verts_.size();
    const std::span<const Vec2> cut = CutSquare(r);
    if (cut.empty()) continue;
    verts_.insert(verts_.end(), cut.begin(), cut.end());
    piece.end = verts_.size();
    pieces_.push_back(piece);
  }
  if (pieces_.empty()) return;
  subdivided_ = false;
  const size_t first = out.size();
  Resolve(0, /*splittable=*/true, with_moments, out);
  if (!subdivided_) return;
  // A subdivided cell gives each polygon one piece per square: summed back into one, in the
  // order the polygons first appear.
  crowded_out_.assign(out.begin() + static_cast<long>(first), out.end());
  out.resize(first);
  merged_.clear();
  for (const CellPiece& piece : crowded_out_) {
    auto [it, added] = merged_.try_emplace(piece.polygon, out.size());
    if (added)
      out.push_back(piece);
    else
      Accumulate(out[it->second].moments, piece.moments);
  }
}

// Polygons whose depth ranges over the whole cell are stacked (each wholly in front of the next:
// small triangles drawn one over another, runway paint over the ground) need no piece cut out
// first, no pairwise test and no painter's order found by tests: the painter cuts the square by
// their crossing edges directly, nearest first. A polygon covering the cell takes what the ones
// in front left, the square less their moments (as the layers' rule above it computes), and hides
// the rest. Most crowded cells of a frame of small polygons are such.
bool CellCoverage::PaintStacked(std::span<const ScreenPolygon> polygons, double cx, double cy,
                                bool with_moments, std::vector<CellPiece>& out) {
  const size_t n = reach_.size();
  if (n > kStackedPieces) return false;  // the quadrants bound a crowded cell's regions
  // Nearest first (an insertion sort: a handful), ties in reach_'s order.
  double nearest[kStackedPieces], farthest[kStackedPieces];
  size_t order[kStackedPieces];
  for (size_t i = 0; i < n; ++i) {
    const ScreenLinear& d = reach_[i].depth;  // over the cell: its centre's value +- r
    const double r = kHalf * (std::abs(d.a) + std::abs(d.b));
    nearest[i] = d.c + r;
    farthest[i] = d.c - r;
    size_t k = i;
    for (; k > 0 && nearest[order[k - 1]] < nearest[i]; --k) order[k] = order[k - 1];
    order[k] = i;
  }
  for (size_t k = 0; k + 1 < n; ++k)
    if (DepthSign(farthest[order[k]], nearest[order[k + 1]]) <= 0) return false;

  StartPainting();
  CellMoments rest = SquareMoments();
  auto covers_cell = [&](size_t k) {
    return reach_[order[k]].edges_begin == reach_[order[k]].edges_end;
  };
  for (size_t k = 0; k < n; ++k) {
    const Reach& r = reach_[order[k]];
    if (covers_cell(k)) {  // takes the rest and hides what is behind
      if (rest.area > 0) out.push_back({r.polygon, rest});
      return true;
    }
    const ScreenPolygon& p = polygons[r.polygon];
    const Box box{p.min_x - cx, p.min_y - cy, p.max_x - cx, p.max_y - cy};
    // The regions left are only needed by a later polygon that does not cover the cell (one that
    // does takes the square less the moments).
    const bool last_cut = k + 1 == n || covers_cell(k + 1);
    CellMoments m;
    PaintInside(std::span(crossing_).subspan(r.edges_begin, r.edges_end - r.edges_begin), box,
                with_moments, /*keep_rest=*/!last_cut, /*max_regions=*/SIZE_MAX, m);
    if (m.area > 0) out.push_back({r.polygon, m});
    rest = {rest.area - m.area, rest.mx - m.mx, rest.my - m.my, rest.mxy - m.mxy};
    if (!last_cut && regions_a_.empty()) return true;
  }
  return true;
}

void CellCoverage::SortReachByPolygon() {
  std::sort(reach_.begin(), reach_.end(),
            [](const Reach& a, const Reach& b) { return a.polygon < b.polygon; });
}

size_t CellCoverage::WorkingBytes() const {
  return HeldBytes(reach_, boxes_, by_left_, pieces_, verts_, clip_, scratch_, crossing_, lines_,
                   in_front_, blockers_, nearest_, farthest_, order_, planes_order_, planes_,
                   plane_rank_, pool_a_, pool_b_, outside_, regions_a_, regions_b_, segments_,
                   breaks_, sums_, inside_, active_, crowded_out_) +
         HeldMapBytes(merged_);
}

// The cell's square cut by each of the polygon's crossing edges, in two fixed buffers; should a
// cut not fit (kClipOverflow), the rest is done in vectors. Empty when under 3 vertices are left.
std::span<const Vec2> CellCoverage::CutSquare(const Reach& r) {
  Vec2* from = clip_buffers_[0];
  Vec2* to = clip_buffers_[1];
  from[0] = {-kHalf, -kHalf}, from[1] = {kHalf, -kHalf}, from[2] = {kHalf, kHalf};
  from[3] = {-kHalf, kHalf};
  size_t n = 4, k = r.edges_begin;
  for (; k < r.edges_end && n >= 3; ++k) {
    const ScreenLinear& e = crossing_[k];
    const size_t cut = ClipByHalfPlane(from, n, e.a, e.b, e.c, to, kClipBuffer);
    if (cut == kClipOverflow) break;
    n = cut;
    std::swap(from, to);
  }
  if (n < 3) return {};
  if (k == r.edges_end) return {from, n};
  clip_.assign(from, from + n);
  for (; k < r.edges_end && !clip_.empty(); ++k) {
    const ScreenLinear& e = crossing_[k];
    ClipByHalfPlane(clip_, e.a, e.b, e.c, scratch_);
  }
  return clip_;
}

CellMoments CellCoverage::SquareMoments() const {
  // Over a rectangle the integral of x y is the area times the centre's x y.
  const double area = (square_.x1 - square_.x0) * (square_.y1 - square_.y0);
  const double xc = 0.5 * (square_.x0 + square_.x1), yc = 0.5 * (square_.y0 + square_.y1);
  return {area, area * xc, area * yc, area * xc * yc};
}

CellMoments CellCoverage::MomentsOf(const Piece& p, bool with_moments) const {
  if (p.full) return SquareMoments();
  return PolygonMoments(std::span(verts_).subspan(p.begin, p.end - p.begin), with_moments);
}

// Painter's algorithm front to back with exact convex clipping: each piece sees what the pieces
// in front of it left of the cell; what it covers is removed from the rest.
bool CellCoverage::PaintFrontToBack(bool with_moments, std::vector<CellPiece>& out) {
  const size_t first = out.size();
  const size_t max_regions = kRegionsAtLeast + kRegionsPerPiece * pieces_.size();
  StartPainting();
  for (size_t index : order_) {
    const Piece& piece = pieces_[index];
    const size_t n = piece.end - piece.begin;
    Box box{INFINITY, INFINITY, -INFINITY, -INFINITY};
    for (size_t k = piece.begin; k < piece.end; ++k) {
      box.x0 = std::min(box.x0, verts_[k].x), box.x1 = std::max(box.x1, verts_[k].x);
      box.y0 = std::min(box.y0, verts_[k].y), box.y1 = std::max(box.y1, verts_[k].y);
    }
    // The lines of the piece's edges that cut the square's inside (not those on its border, nor
    // repeated vertices), once for all regions.
    lines_.clear();
    for (size_t i = 0; i < n; ++i) {
      const Vec2& p = verts_[piece.begin + i];
      const Vec2& q = verts_[piece.begin + (i + 1 == n ? 0 : i + 1)];
      if ((p.x == q.x && (p.x == square_.x0 || p.x == square_.x1)) ||
          (p.y == q.y && (p.y == square_.y0 || p.y == square_.y1)))
        continue;  // on the square's border: cuts nothing inside
      const double a = -(q.y - p.y), b = q.x - p.x;
      if (a == 0 && b == 0) continue;
      lines_.push_back({a, b, -(a * p.x + b * p.y)});
    }
    CellMoments visible;
    if (!PaintInside(lines_, box, with_moments, /*keep_rest=*/true, max_regions, visible)) {
      out.resize(first);
      return false;
    }
    if (visible.area > kSliverArea * SquareMoments().area) out.push_back({piece.polygon, visible});
    if (regions_a_.empty()) break;
  }
  return true;
}

void CellCoverage::StartPainting() {
  pool_a_.resize(4);
  pool_a_[0] = {square_.x0, square_.y0}, pool_a_[1] = {square_.x1, square_.y0};
  pool_a_[2] = {square_.x1, square_.y1}, pool_a_[3] = {square_.x0, square_.y1};
  regions_a_.resize(1);
  regions_a_[0] = {0, 4};
}

bool CellCoverage::PaintInside(std::span<const ScreenLinear> lines, const Box& box,
                               bool with_moments, bool keep_rest, size_t max_regions,
                               CellMoments& visible) {
  visible = {};
  if (!keep_rest) {  // only what lies inside: clipped, not split
    for (const auto& [begin, end] : regions_a_) {
      const std::span<const Vec2> region(pool_a_.data() + begin, end - begin);
      Vec2* from = clip_buffers_[0];
      Vec2* to = clip_buffers_[1];
      size_t count = region.size() + 2 <= kClipBuffer ? region.size() : kClipOverflow;
      if (count != kClipOverflow) CopyVertices(region, from);
      for (size_t i = 0; i < lines.size() && count >= 3 && count != kClipOverflow; ++i) {
        count = ClipByHalfPlane(from, count, lines[i].a, lines[i].b, lines[i].c, to, kClipBuffer);
        std::swap(from, to);
      }
      if (count != kClipOverflow) {
        if (count >= 3) Accumulate(visible, PolygonMoments({from, count}, with_moments));
        continue;
      }
      clip_.assign(region.begin(), region.end());  // a cut would not fit: again, in vectors
      for (size_t i = 0; i < lines.size() && !clip_.empty(); ++i)
        ClipByHalfPlane(clip_, lines[i].a, lines[i].b, lines[i].c, scratch_);
      if (!clip_.empty()) Accumulate(visible, PolygonMoments(clip_, with_moments));
    }
    return true;
  }
  const double sliver = kSliverArea * (square_.x1 - square_.x0) * (square_.y1 - square_.y0);
  pool_b_.clear();
  regions_b_.clear();
  auto keep = [&](std::span<const Vec2> region) {
    const size_t at = pool_b_.size();
    regions_b_.push_back({at, at + region.size()});
    pool_b_.resize(at + region.size());
    CopyVertices(region, pool_b_.data() + at);
  };
  for (const auto& [begin, end] : regions_a_) {
    const std::span<const Vec2> region(pool_a_.data() + begin, end - begin);
    // A region beside the piece's bounding box stays whole: cutting it along the lines of the
    // piece's edges would only multiply the regions (a crowded cell's painter would then grow
    // them without bound).
    double rx0 = INFINITY, ry0 = INFINITY, rx1 = -INFINITY, ry1 = -INFINITY;
    for (const Vec2& v : region) {
      rx0 = std::min(rx0, v.x), rx1 = std::max(rx1, v.x);
      ry0 = std::min(ry0, v.y), ry1 = std::max(ry1, v.y);
    }
    if (rx1 <= box.x0 || rx0 >= box.x1 || ry1 <= box.y0 || ry0 >= box.y1) {
      keep(region);
      continue;
    }
    // The region cut by each line: the part outside a line is kept, the part inside goes on to
    // the next line, and what is inside all of them is the piece's visible part. In the fixed
    // buffers while the cuts fit; from the line where one would not, in vectors.
    size_t i = 0;
    if (region.size() + 2 <= kClipBuffer) {
      Vec2* inside = clip_buffers_[0];
      Vec2* next = clip_buffers_[1];
      Vec2* outside = clip_buffers_[2];
      CopyVertices(region, inside);
      size_t count = region.size();
      for (; i < lines.size() && count >= 3; ++i) {
        const ScreenLinear& e = lines[i];
        size_t in_count, out_count;
        if (!SplitByLine(inside, count, e.a, e.b, e.c, next, in_count, outside, out_count,
                         kClipBuffer))
          break;
        // A sliver (a vertex on the line, an edge along one painted before) is nothing left to
        // paint.
        const std::span<const Vec2> outside_part(outside, out_count);
        if (out_count >= 3 && PolygonMoments(outside_part, false).area > sliver) keep(outside_part);
        count = in_count;
        std::swap(inside, next);
      }
      if (i == lines.size() || count < 3) {
        if (count >= 3) Accumulate(visible, PolygonMoments({inside, count}, with_moments));
        if (regions_b_.size() > max_regions) return false;
        continue;
      }
      clip_.assign(inside, inside + count);
    } else {
      clip_.assign(region.begin(), region.end());
    }
    for (; i < lines.size() && !clip_.empty(); ++i) {
      const ScreenLinear& e = lines[i];
      outside_.assign(clip_.begin(), clip_.end());
      ClipByHalfPlane(outside_, -e.a, -e.b, -e.c, scratch_);
      if (outside_.size() >= 3 && PolygonMoments(outside_, false).area > sliver) keep(outside_);
      ClipByHalfPlane(clip_, e.a, e.b, e.c, scratch_);
    }
    if (!clip_.empty()) Accumulate(visible, PolygonMoments(clip_, with_moments));
    if (regions_b_.size() > max_regions) return false;
  }
  std::swap(pool_a_, pool_b_);
  std::swap(regions_a_, regions_b_);
  return true;
}

}  // namespace aperture
