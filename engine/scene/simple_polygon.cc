#include "scene/simple_polygon.h"

#include <algorithm>
#include <set>

#include "absl/strings/str_cat.h"

namespace aperture {
namespace {

// > 0 when o -> a -> b turns left (counter-clockwise).
double Orient(const Vec2& o, const Vec2& a, const Vec2& b) {
  return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
}

int Sign(double v) { return (v > 0) - (v < 0); }

// The sweep runs left to right; points are ordered by x, then y (a vertical edge's lower end is
// its left end).
bool Before(const Vec2& p, const Vec2& q) { return p.x < q.x || (p.x == q.x && p.y < q.y); }

struct Segment {
  Vec2 left, right;
  int edge;  // index of the polygon edge
};

// p lies on the segment a-b, given that it lies on the line through them.
bool WithinBox(const Vec2& a, const Vec2& b, const Vec2& p) {
  return std::min(a.x, b.x) <= p.x && p.x <= std::max(a.x, b.x) && std::min(a.y, b.y) <= p.y &&
         p.y <= std::max(a.y, b.y);
}

// Closed segments a-b and c-d share a point.
bool Meet(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d) {
  const int o1 = Sign(Orient(a, b, c)), o2 = Sign(Orient(a, b, d));
  const int o3 = Sign(Orient(c, d, a)), o4 = Sign(Orient(c, d, b));
  if (o1 != o2 && o3 != o4) return true;
  return (o1 == 0 && WithinBox(a, b, c)) || (o2 == 0 && WithinBox(a, b, d)) ||
         (o3 == 0 && WithinBox(c, d, a)) || (o4 == 0 && WithinBox(c, d, b));
}

class SimplicitySweep {
 public:
  explicit SimplicitySweep(const std::vector<Vec2>& p) : p_(p), n_(static_cast<int>(p.size())) {}

  absl::Status Run() {
    std::vector<Segment> segments;
    for (int i = 0; i < n_; ++i) {
      const Vec2 &a = p_[i], &b = p_[Next(i)];
      if (a.x == b.x && a.y == b.y) continue;  // a repeated vertex
      segments.push_back(Before(a, b) ? Segment{a, b, i} : Segment{b, a, i});
    }
    if (segments.size() < 3) return absl::OkStatus();  // the degenerate check speaks for these
    // Events: each segment enters at its left end and leaves at its right; at one point, entries
    // come first, so segments that touch there are in the status together and get compared.
    struct Event {
      Vec2 at;
      bool enters;
      int segment;
    };
    std::vector<Event> events;
    events.reserve(2 * segments.size());
    for (int s = 0; s < static_cast<int>(segments.size()); ++s) {
      events.push_back({segments[s].left, true, s});
      events.push_back({segments[s].right, false, s});
    }
    std::sort(events.begin(), events.end(), [](const Event& a, const Event& b) {
      if (Before(a.at, b.at)) return true;
      if (Before(b.at, a.at)) return false;
      return a.enters && !b.enters;
    });

    auto below = [&segments](int a, int b) { return Below(segments[a], segments[b]); };
    std::set<int, decltype(below)> status(below);
    std::vector<std::set<int, decltype(below)>::iterator> where(segments.size(), status.end());
    for (const Event& event : events) {
      const Segment& s = segments[event.segment];
      if (event.enters) {
        auto next = status.lower_bound(event.segment);
        if (next != status.end())
          if (auto crossing = Check(s, segments[*next]); !crossing.ok()) return crossing;
        if (next != status.begin())
          if (auto crossing = Check(s, segments[*std::prev(next)]); !crossing.ok()) return crossing;
        where[event.segment] = status.insert(next, event.segment);
      } else {
        auto at = where[event.segment];
        auto next = std::next(at);
        if (next != status.end() && at != status.begin())
          if (auto crossing = Check(segments[*std::prev(at)], segments[*next]); !crossing.ok())
            return crossing;
        status.erase(at);
      }
    }
    return absl::OkStatus();
  }

 private:
  int Next(int i) const { return i + 1 == n_ ? 0 : i + 1; }

  // The order of the sweep status: a is below b on the sweep line where both are present. The one
  // that entered later is compared with the other's line at its left end (ties: at its right end).
  static bool Below(const Segment& a, const Segment& b) {
    if (a.edge == b.edge) return false;
    if (!Before(a.left, b.left) && !Before(b.left, a.left)) {  // the same left end: by slope
      const double o = Orient(a.left, a.right, b.right);
      if (o != 0) return o > 0;
      return a.edge < b.edge;  // overlapping: Check reports them, any consistent order will do
    }
    if (Before(b.left, a.left)) {  // a entered later
      const double o = Orient(b.left, b.right, a.left);
      if (o != 0) return o < 0;
      const double r = Orient(b.left, b.right, a.right);
      if (r != 0) return r < 0;
      return a.edge < b.edge;
    }
    const double o = Orient(a.left, a.right, b.left);
    if (o != 0) return o > 0;
    const double r = Orient(a.left, a.right, b.right);
    if (r != 0) return r > 0;
    return a.edge < b.edge;
  }

  // Neighbours along the boundary (edge i and i + 1, skipping edges of length 0 between them).
  bool Adjacent(int a, int b) const {
    auto after = [this](int e, int f) {
      for (int k = Next(e);; k = Next(k)) {
        if (k == f) return true;
        const Vec2 &u = p_[k], &v = p_[Next(k)];
        if (u.x != v.x || u.y != v.y || k == e) return false;
      }
    };
    return after(a, b) || after(b, a);
  }

  absl::Status Check(const Segment& a, const Segment& b) const {
    if (!Meet(a.left, a.right, b.left, b.right)) return absl::OkStatus();
    if (Adjacent(a.edge, b.edge)) {
      // Neighbours share a vertex; they may not fold back over each other.
      const bool collinear =
          Orient(a.left, a.right, b.left) == 0 && Orient(a.left, a.right, b.right) == 0;
      if (!collinear) return absl::OkStatus();
      const Vec2 along{a.right.x - a.left.x, a.right.y - a.left.y};
      const Vec2 other{b.right.x - b.left.x, b.right.y - b.left.y};
      // Collinear neighbours continue straight on (fine) when they point the same way and meet
      // end to start; otherwise they overlap.
      const bool same_way = along.x * other.x + along.y * other.y > 0;
      const bool end_to_start = (a.right.x == b.left.x && a.right.y == b.left.y) ||
                                (b.right.x == a.left.x && b.right.y == a.left.y);
      if (same_way && end_to_start) return absl::OkStatus();
      return absl::InvalidArgumentError(
          absl::StrCat("polygon is self-intersecting: edges ", std::min(a.edge, b.edge), " and ",
                       std::max(a.edge, b.edge), " fold back over each other"));
    }
    return absl::InvalidArgumentError(absl::StrCat(
        "polygon is self-intersecting: edges ", std::min(a.edge, b.edge), " and ",
        std::max(a.edge, b.edge), " cross or touch (edge i runs from vertex i to vertex i + 1)"));
  }

  const std::vector<Vec2>& p_;
  const int n_;
};

}  // namespace

absl::Status CheckSimplePolygon(const std::vector<Vec2>& polygon) {
  if (polygon.size() < 3) return absl::OkStatus();
  return SimplicitySweep(polygon).Run();
}

}  // namespace aperture
