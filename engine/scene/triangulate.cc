#include "scene/triangulate.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <set>

namespace aperture {
namespace {

// > 0 when o -> a -> b turns left (counter-clockwise).
double Orient(const Vec2& o, const Vec2& a, const Vec2& b) {
  return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
}

// The sweep runs from top to bottom. Ties in y are broken by x (smaller x is above): a rotation
// of the plane by an infinitesimal angle, so no two vertices are level and no edge horizontal.
bool Above(const Vec2& p, const Vec2& q) { return p.y > q.y || (p.y == q.y && p.x < q.x); }

// de Berg, Cheong, van Kreveld, Overmars, "Computational Geometry", ch. 3: a sweep splits the
// polygon into y-monotone pieces by diagonals (O(n log n)), then each piece is triangulated by a
// stack walk down its two chains (linear). Vertices are indices into `p`, counter-clockwise.
class MonotoneTriangulator {
 public:
  explicit MonotoneTriangulator(const std::vector<Vec2>& p) : p_(p), n_(p.size()) {}

  absl::StatusOr<std::vector<std::array<int, 3>>> Run() {
    if (!Partition()) return Fail();
    std::vector<std::array<int, 3>> triangles;
    triangles.reserve(n_ - 2);
    if (!TriangulateFaces(triangles) || triangles.size() != n_ - 2) return Fail();
    return triangles;
  }

 private:
  enum class Kind { kStart, kSplit, kEnd, kMerge, kRegular };

  static absl::Status Fail() {
    return absl::InvalidArgumentError("polygon is self-intersecting (no valid triangulation)");
  }
  size_t Next(size_t i) const { return i + 1 == n_ ? 0 : i + 1; }
  size_t Prev(size_t i) const { return i == 0 ? n_ - 1 : i - 1; }

  Kind KindOf(size_t i) const {
    const Vec2 &u = p_[Prev(i)], &v = p_[i], &w = p_[Next(i)];
    const bool u_below = Above(v, u), w_below = Above(v, w);
    const bool convex = Orient(u, v, w) > 0;
    if (u_below && w_below) return convex ? Kind::kStart : Kind::kSplit;
    if (!u_below && !w_below) return convex ? Kind::kEnd : Kind::kMerge;
    return Kind::kRegular;
  }

  // Edge i runs from vertex i to i + 1. The sweep status holds the edges the sweep line crosses
  // that have the interior on their east, ordered west to east; `query_` stands for a point.
  // Orientation is invariant under the infinitesimal rotation, so these tests are exact as is.
  const Vec2& Upper(size_t e) const { return Above(p_[e], p_[Next(e)]) ? p_[e] : p_[Next(e)]; }
  const Vec2& Lower(size_t e) const { return Above(p_[e], p_[Next(e)]) ? p_[Next(e)] : p_[e]; }
  // > 0: q lies east of edge e (left of it travelled downwards).
  double EastOf(size_t e, const Vec2& q) const { return Orient(Upper(e), Lower(e), q); }

  struct WestToEast {
    const MonotoneTriangulator* t;
    bool operator()(size_t a, size_t b) const { return t->West(a, b); }
  };
  static constexpr size_t kQuery = static_cast<size_t>(-1);
  bool West(size_t a, size_t b) const {
    if (a == b) return false;
    if (a == kQuery) return EastOf(b, query_) < 0;
    if (b == kQuery) return EastOf(a, query_) > 0;
    // Test the edge that starts lower against the other (they share at most an endpoint).
    if (!Above(Upper(a), Upper(b))) {
      double s = EastOf(b, Upper(a));
      if (s == 0) s = EastOf(b, Lower(a));
      return s < 0;
    }
    double s = EastOf(a, Upper(b));
    if (s == 0) s = EastOf(a, Lower(b));
    return s > 0;
  }

  // The status edge directly west of vertex v, or kQuery when there is none.
  size_t WestOf(size_t v) {
    query_ = p_[v];
    auto it = status_.lower_bound(kQuery);
    if (it == status_.begin()) return kQuery;
    return *--it;
  }

  void Diagonal(size_t a, size_t b) {
    adjacency_[a].push_back(b);
    adjacency_[b].push_back(a);
  }

  bool Partition() {
    adjacency_.assign(n_, {});
    for (size_t i = 0; i < n_; ++i) {
      adjacency_[i].push_back(Next(i));
      adjacency_[Next(i)].push_back(i);
    }
    std::vector<size_t> order(n_);
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return Above(p_[a], p_[b]); });
    std::vector<Kind> kind(n_);
    for (size_t i = 0; i < n_; ++i) kind[i] = KindOf(i);
    helper_.assign(n_, 0);
    status_ = std::set<size_t, WestToEast>(WestToEast{this});
    auto merge_helper = [&](size_t e) { return kind[helper_[e]] == Kind::kMerge; };
    auto remove = [&](size_t e) { return status_.erase(e) == 1; };
    for (size_t v : order) {
      const size_t prev_edge = Prev(v);
      switch (kind[v]) {
        case Kind::kStart:
          status_.insert(v);
          helper_[v] = v;
          break;
        case Kind::kEnd:
          if (merge_helper(prev_edge)) Diagonal(v, helper_[prev_edge]);
          if (!remove(prev_edge)) return false;
          break;
        case Kind::kSplit: {
          const size_t west = WestOf(v);
          if (west == kQuery) return false;
          Diagonal(v, helper_[west]);
          helper_[west] = v;
          status_.insert(v);
          helper_[v] = v;
          break;
        }
        case Kind::kMerge: {
          if (merge_helper(prev_edge)) Diagonal(v, helper_[prev_edge]);
          if (!remove(prev_edge)) return false;
          const size_t west = WestOf(v);
          if (west == kQuery) return false;
          if (merge_helper(west)) Diagonal(v, helper_[west]);
          helper_[west] = v;
          break;
        }
        case Kind::kRegular:
          if (Above(p_[Prev(v)], p_[v])) {  // going down: the interior is east of v
            if (merge_helper(prev_edge)) Diagonal(v, helper_[prev_edge]);
            if (!remove(prev_edge)) return false;
            status_.insert(v);
            helper_[v] = v;
          } else {
            const size_t west = WestOf(v);
            if (west == kQuery) return false;
            if (merge_helper(west)) Diagonal(v, helper_[west]);
            helper_[west] = v;
          }
          break;
      }
    }
    return status_.empty();
  }

  // Walks the faces of polygon edges plus diagonals (each face keeps the interior on its left)
  // and triangulates each, a y-monotone polygon.
  bool TriangulateFaces(std::vector<std::array<int, 3>>& out) {
    // Neighbours counter-clockwise by angle around each vertex.
    for (size_t v = 0; v < n_; ++v) {
      auto& nb = adjacency_[v];
      std::sort(nb.begin(), nb.end(), [&](size_t a, size_t b) {
        return std::atan2(p_[a].y - p_[v].y, p_[a].x - p_[v].x) <
               std::atan2(p_[b].y - p_[v].y, p_[b].x - p_[v].x);
      });
      nb.erase(std::unique(nb.begin(), nb.end()), nb.end());  // a diagonal added twice
    }
    // Half-edge v -> adjacency_[v][k] visited?
    std::vector<std::vector<char>> visited(n_);
    for (size_t v = 0; v < n_; ++v) visited[v].assign(adjacency_[v].size(), 0);
    auto slot = [&](size_t from, size_t to) {
      const auto& nb = adjacency_[from];
      return static_cast<size_t>(std::find(nb.begin(), nb.end(), to) - nb.begin());
    };
    std::vector<size_t> face;
    for (size_t start = 0; start < n_; ++start) {
      for (size_t k = 0; k < adjacency_[start].size(); ++k) {
        if (visited[start][k]) continue;
        const size_t first_to = adjacency_[start][k];
        // The outside face runs along polygon edges clockwise: never start there.
        if (first_to == Prev(start)) continue;
        face.clear();
        size_t from = start, to = first_to;
        while (true) {
          const size_t s = slot(from, to);
          if (visited[from][s]) return false;  // a walk that does not close: not simple
          visited[from][s] = 1;
          face.push_back(from);
          if (face.size() > n_) return false;
          // Next edge: the neighbour of `to` just clockwise of `from`.
          const auto& nb = adjacency_[to];
          const size_t back = slot(to, from);
          const size_t next = nb[back == 0 ? nb.size() - 1 : back - 1];
          from = to;
          to = next;
          if (from == start && to == first_to) break;
        }
        if (!TriangulateMonotone(face, out)) return false;
      }
    }
    return true;
  }

  // de Berg's TriangulateMonotonePolygon on one counter-clockwise face.
  bool TriangulateMonotone(const std::vector<size_t>& face, std::vector<std::array<int, 3>>& out) {
    const size_t m = face.size();
    if (m < 3) return false;
    size_t top = 0, bottom = 0;
    for (size_t i = 1; i < m; ++i) {
      if (Above(p_[face[i]], p_[face[top]])) top = i;
      if (Above(p_[face[bottom]], p_[face[i]])) bottom = i;
    }
    // Counter-clockwise from the top runs down the west chain to the bottom; the east chain is
    // the rest. Merge the two chains, top to bottom.
    struct Entry {
      size_t v;
      bool west;
    };
    std::vector<Entry> sorted;
    sorted.reserve(m);
    size_t w = top, e = top == 0 ? m - 1 : top - 1;
    sorted.push_back({face[top], true});
    while (sorted.size() < m) {
      const size_t wn = w + 1 == m ? 0 : w + 1;
      const bool west_left = w != bottom;
      const bool east_left = e != bottom && e != top;
      if (west_left && (!east_left || Above(p_[face[wn]], p_[face[e]]))) {
        sorted.push_back({face[wn], true});
        w = wn;
      } else if (east_left) {
        sorted.push_back({face[e], false});
        e = e == 0 ? m - 1 : e - 1;
      } else {
        return false;  // not monotone: the chains do not meet at the bottom
      }
    }
    sorted.back().west = true;  // the bottom closes both chains
    auto emit = [&](size_t a, size_t b, size_t c) {
      const double o = Orient(p_[a], p_[b], p_[c]);
      if (o >= 0)
        out.push_back({static_cast<int>(a), static_cast<int>(b), static_cast<int>(c)});
      else
        out.push_back({static_cast<int>(a), static_cast<int>(c), static_cast<int>(b)});
    };
    std::vector<Entry> stack = {sorted[0], sorted[1]};
    for (size_t j = 2; j + 1 < m; ++j) {
      const Entry u = sorted[j];
      if (u.west != stack.back().west) {
        // Across to the other chain: a fan from u to every vertex on the stack.
        for (size_t k = 0; k + 1 < stack.size(); ++k) emit(u.v, stack[k].v, stack[k + 1].v);
        const Entry last = stack.back();
        stack = {last, u};
      } else {
        Entry popped = stack.back();
        stack.pop_back();
        // Down the same chain: cut off triangles while the diagonal from u lies inside.
        while (!stack.empty()) {
          const Entry& s = stack.back();
          const double o = Orient(p_[u.v], p_[popped.v], p_[s.v]);
          if (u.west ? o >= 0 : o <= 0) break;  // popped is reflex: the diagonal would leave
          emit(u.v, popped.v, s.v);
          popped = s;
          stack.pop_back();
        }
        stack.push_back(popped);
        stack.push_back(u);
      }
    }
    const size_t last = sorted[m - 1].v;
    for (size_t k = 0; k + 1 < stack.size(); ++k) emit(last, stack[k].v, stack[k + 1].v);
    return true;
  }

  const std::vector<Vec2>& p_;
  const size_t n_;
  std::vector<std::vector<size_t>> adjacency_;
  std::vector<size_t> helper_;
  Vec2 query_;
  std::set<size_t, WestToEast> status_{WestToEast{this}};
};

}  // namespace

double SignedArea(std::span<const Vec2> poly) {
  double area = 0;
  for (size_t i = 0, n = poly.size(); i < n; ++i) {
    const Vec2& a = poly[i];
    const Vec2& b = poly[(i + 1) % n];
    area += a.x * b.y - b.x * a.y;
  }
  return 0.5 * area;
}

bool IsConvex(std::span<const Vec2> poly) {
  const size_t n = poly.size();
  const double sign = SignedArea(poly) >= 0 ? 1.0 : -1.0;
  // Every turn the same way, and once round in all: a pentagram turns the same way at every
  // vertex but goes round twice (4 pi of turning), and is not convex (nor simple).
  double turning = 0;
  for (size_t i = 0; i < n; ++i) {
    const Vec2 &a = poly[i], &b = poly[(i + 1) % n], &c = poly[(i + 2) % n];
    const double cross = Orient(a, b, c);
    if (sign * cross < 0) return false;
    const double dot = (b.x - a.x) * (c.x - b.x) + (b.y - a.y) * (c.y - b.y);
    if (cross == 0 && dot < 0) return false;  // folds back on itself
    turning += std::atan2(sign * cross, dot);
  }
  return std::abs(turning - 2 * M_PI) < 1e-6;
}

absl::StatusOr<std::vector<std::array<int, 3>>> TriangulatePolygon(const std::vector<Vec2>& input) {
  const size_t n = input.size();
  if (n < 3) return absl::InvalidArgumentError("a polygon needs at least 3 vertices");
  if (n == 3) return std::vector<std::array<int, 3>>{{0, 1, 2}};
  // Work counter-clockwise: a clockwise polygon is triangulated reversed, indices mapped back.
  const bool reversed = SignedArea(input) < 0;
  std::vector<Vec2> ccw = input;
  if (reversed) std::reverse(ccw.begin(), ccw.end());
  auto triangles = MonotoneTriangulator(ccw).Run();
  if (!triangles.ok() || !reversed) return triangles;
  for (auto& t : *triangles)
    for (int& i : t) i = static_cast<int>(n) - 1 - i;
  return triangles;
}

}  // namespace aperture
