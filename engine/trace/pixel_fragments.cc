#include "trace/pixel_fragments.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace aperture {
namespace {

// One axis of the construction: `along` picks the coordinate the grid lines cross (x for Lx).
// Fills `out` with the group rectangles and returns their total area. `l` is a power of two (the
// grid of level k, 2^-k).
//
// Steps 3-7: the list L = {a, b, c, d, crossings of the edges with the lines key = m l}, sorted by
// the key and grouped by grid cell (a point on a line joins both cells it separates), each group
// bounded by a rectangle. Sorting only serves to bring a cell's points together, so each point
// goes straight to its cell's rectangle instead (the same rectangles, without the sort): cell
// `first` is the one of the smallest key (minus one when it lies on a line), out[cell - first].
double BuildGroups(const std::array<TexPoint, 4>& quad, double l, bool along_x,
                   std::vector<TexRect>* out) {
  auto key = [&](const TexPoint& p) { return along_x ? p.x : p.z; };
  auto other = [&](const TexPoint& p) { return along_x ? p.z : p.x; };
  double kmin = key(quad[0]), kmax = kmin;
  for (const TexPoint& p : quad) kmin = std::min(kmin, key(p)), kmax = std::max(kmax, key(p));
  const double first = std::ceil(kmin / l) - 1;
  out->assign(static_cast<size_t>(std::floor(kmax / l) - first) + 1,
              TexRect{INFINITY, INFINITY, -INFINITY, -INFINITY});
  // The rectangle of a cell, null outside [kmin, kmax] (not reached: every key lies there).
  auto rect_of = [&](double cell) -> TexRect* {
    const size_t index = static_cast<size_t>(cell - first);
    return index < out->size() ? &(*out)[index] : nullptr;
  };
  auto include = [&](TexRect& r, double k, double o) {
    const double x = along_x ? k : o, z = along_x ? o : k;
    r.x0 = std::min(r.x0, x), r.x1 = std::max(r.x1, x);
    r.z0 = std::min(r.z0, z), r.z1 = std::max(r.z1, z);
  };
  auto add = [&](double cell, double k, double o) {
    if (TexRect* r = rect_of(cell)) include(*r, k, o);
  };
  // Two points into one cell in one update (a local copy, stored once).
  auto add_two = [&](double cell, double k, double o, double k1, double o1) {
    TexRect* r = rect_of(cell);
    if (r == nullptr) return;
    TexRect both = *r;
    include(both, k, o);
    include(both, k1, o1);
    *r = both;
  };
  auto place = [&](double k, double o) {
    const double c = k / l, cell = std::floor(c);
    if (c == cell) add(cell - 1, k, o);  // on a grid line: also the cell before it
    add(cell, k, o);
  };
  for (int e = 0; e < 4; ++e) {
    const TexPoint &p = quad[e], &q = quad[(e + 1) % 4];
    place(key(p), other(p));
    const double kp = key(p), kq = key(q);
    if (kp == kq) continue;  // parallel to the lines: its ends are vertices already
    const double lo = std::min(kp, kq), hi = std::max(kp, kq);
    // The crossing with line m joins cells m - 1 and m (l is a power of two, so k / l is m
    // exactly: what `place` would find, without its division). Cell m takes the crossings with
    // lines m and m + 1 in that order, in one update.
    auto crossing = [&](double m) {
      const double k = m * l, t = (k - kp) / (kq - kp);
      return std::pair{k, other(p) + t * (other(q) - other(p))};
    };
    double m = std::ceil(lo / l);
    if (!(m * l <= hi)) continue;
    auto [k, o] = crossing(m);
    add(m - 1, k, o);
    for (;; m += 1) {
      if (!((m + 1) * l <= hi)) {
        add(m, k, o);
        break;
      }
      const auto [k1, o1] = crossing(m + 1);
      add_two(m, k, o, k1, o1);
      k = k1, o = o1;
    }
  }
  // A cell holding only points on its border line has no width: not a fragment.
  double area = 0;
  size_t kept = 0;
  for (const TexRect& r : *out) {
    if (!(r.x1 > r.x0 && r.z1 > r.z0)) continue;
    area += r.Area();
    (*out)[kept++] = r;
  }
  out->resize(kept);
  return area;
}

}  // namespace

int FragmentLevel(double delta, double quad_area, double quad_perimeter) {
  // seed 003, eq. 9
  return static_cast<int>(std::ceil(-std::log2(delta * quad_area / quad_perimeter) - 1.0));
}

void BuildFragments(const std::array<TexPoint, 4>& quad, const FragmentOptions& options,
                    FragmentSet* out) {
  out->fragments.clear();
  // S and P of abcd (shoelace; either orientation).
  double twice_area = 0, perimeter = 0;
  double x0 = quad[0].x, x1 = x0, z0 = quad[0].z, z1 = z0;
  for (int e = 0; e < 4; ++e) {
    const TexPoint &p = quad[e], &q = quad[(e + 1) % 4];
    twice_area += p.x * q.z - q.x * p.z;
    perimeter += std::hypot(q.x - p.x, q.z - p.z);
    x0 = std::min(x0, p.x), x1 = std::max(x1, p.x), z0 = std::min(z0, p.z), z1 = std::max(z1, p.z);
  }
  out->quad_area = 0.5 * std::abs(twice_area);
  out->quad_perimeter = perimeter;
  const double extent = std::max(x1 - x0, z1 - z0);
  if (!(out->quad_area > 1e-12 * perimeter * perimeter)) {
    // Degenerate (a pixel seen edge-on): the bounding box, or nothing when that is empty too.
    out->level = 0;
    out->columns = true;
    const TexRect box{x0, z0, x1, z1};
    out->area = box.Area();
    if (out->area > 0) out->fragments.push_back(box);
    return;
  }
  thread_local std::vector<TexRect> gz;  // scratch, kept between calls
  if (options.rule == FragmentLevelRule::kEquationNine) {
    // Step 1-2: level k from delta (eq. 9), within the limits.
    int k = std::min(FragmentLevel(options.delta, out->quad_area, perimeter), options.max_level);
    while (k > -60 && extent * std::ldexp(1.0, k) > options.max_cells) --k;
    out->level = k;
    const double l = std::ldexp(1.0, -k);
    // Steps 3-7 along each axis; step 8: keep the set of smaller area.
    const double area_x = BuildGroups(quad, l, true, &out->fragments);
    const double area_z = BuildGroups(quad, l, false, &gz);
    out->columns = area_x <= area_z;
    out->area = out->columns ? area_x : area_z;
    if (!out->columns) out->fragments.swap(gz);
    return;
  }
  // Per axis: the coarsest level whose bound keeps delta (see FragmentLevelRule), refined while
  // the set built exceeds it, within the limits.
  const double bound = out->quad_area * (1 + options.delta);
  auto build = [&](bool along_x, std::vector<TexRect>* set, int* level) {
    const double along = along_x ? x1 - x0 : z1 - z0, across = along_x ? z1 - z0 : x1 - x0;
    int k =
        std::min(static_cast<int>(std::ceil(-std::log2(options.delta * out->quad_area / across))),
                 options.max_level);
    while (k > -60 && along * std::ldexp(1.0, k) > options.max_cells) --k;
    double area = BuildGroups(quad, std::ldexp(1.0, -k), along_x, set);
    while (area > bound && k < options.max_level &&
           along * std::ldexp(1.0, k + 1) <= options.max_cells) {
      ++k;
      area = BuildGroups(quad, std::ldexp(1.0, -k), along_x, set);
    }
    *level = k;
    return area;
  };
  int level_x = 0, level_z = 0;
  const double area_x = build(true, &out->fragments, &level_x);
  const double area_z = build(false, &gz, &level_z);
  const size_t nx = out->fragments.size(), nz = gz.size();
  // A set within the bound (the other capped by max_cells); both within it, the fewer fragments
  // (then the smaller area); neither (both capped), the smaller area.
  const bool within_x = area_x <= bound, within_z = area_z <= bound;
  out->columns = within_x != within_z   ? within_x
                 : within_x && nx != nz ? nx < nz
                                        : area_x <= area_z;
  out->area = out->columns ? area_x : area_z;
  out->level = out->columns ? level_x : level_z;
  if (!out->columns) out->fragments.swap(gz);
}

void ChildFragments(const TexRect& f, std::vector<TexRect>* out) {
  const double i0 = std::floor(f.x0), j0 = std::floor(f.z0);
  for (double j = j0; j < f.z1; j += 1) {
    const double z0 = std::max(f.z0, j) - j, z1 = std::min(f.z1, j + 1) - j;
    if (z1 <= z0) continue;
    for (double i = i0; i < f.x1; i += 1) {
      const double x0 = std::max(f.x0, i) - i, x1 = std::min(f.x1, i + 1) - i;
      if (x1 > x0) out->push_back({x0, z0, x1, z1});
    }
  }
}

}  // namespace aperture
