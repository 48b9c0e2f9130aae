#include "trace/polygon_integral.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace aperture {
namespace {

// Green's theorem holds for any simple polygon: a quad is one unless a pair of opposite sides
// cross (a bow tie, whose two loops would count with opposite signs). Near the horizon a
// projection's short sides are nearly collinear with the long ones, so convexity is not asked.
bool Simple(const std::array<TexPoint, 4>& q, double* twice_area) {
  auto side = [](const TexPoint& a, const TexPoint& b, const TexPoint& p) {
    return (b.x - a.x) * (p.z - a.z) - (b.z - a.z) * (p.x - a.x);
  };
  auto cross = [&](const TexPoint& a, const TexPoint& b, const TexPoint& c, const TexPoint& d) {
    return side(a, b, c) * side(a, b, d) < 0 && side(c, d, a) * side(c, d, b) < 0;
  };
  double area = 0;
  for (int k = 0; k < 4; ++k) area += q[k].x * q[(k + 1) % 4].z - q[(k + 1) % 4].x * q[k].z;
  *twice_area = area;
  return !cross(q[0], q[1], q[2], q[3]) && !cross(q[1], q[2], q[3], q[0]);
}

// Integrates the texture over the band between texel lines `n` and n + 1 (rows when `rows`),
// along the piece of an edge from (a1, b1) to (a2, b2) within it: a along the lines, b across
// (t = b - n from 0 to 1). The integrand is (1 - t) G_n(a) + t G_(n+1)(a) db. The texture
// repeats: line n is the table's line n mod its period, and past a period along a, G grows by the
// line's integral over a whole period, Gp, once per period.
class BandIntegrator {
 public:
  BandIntegrator(const SummedAreaTable& table, bool rows)
      : table_(table),
        rows_(rows),
        cells_(rows ? table.width() : table.height()),
        lines_(rows ? table.height() : table.width()) {}

  // Steps of an edge from (a1, b1) to (a2, b2) in this form: the bands it crosses, and the
  // periods along a within them.
  int Steps(double a1, double b1, double a2, double b2) const {
    const double bands = std::abs(std::floor(b2) - std::floor(b1));
    if (a1 >= -1 && a1 <= cells_ - 1 && a2 >= -1 && a2 <= cells_ - 1)
      return static_cast<int>(bands);  // within the first period (InBand's shortcut)
    return static_cast<int>(
        bands + std::abs(std::floor((a2 + 1) / cells_) - std::floor((a1 + 1) / cells_)));
  }

  // The edge from (a1, b1) to (a2, b2), cut at the bands it crosses; adds to `sum`.
  void Edge(double a1, double b1, double a2, double b2, double* sum) const {
    if (b1 == b2) return;
    const double n1 = std::floor(b1), n2 = std::floor(b2), dir = n2 >= n1 ? 1 : -1;
    const double slope = (a2 - a1) / (b2 - b1);
    double pa = a1, pb = b1;
    for (double n = n1;; n += dir) {
      double na = a2, nb = b2;
      if (n != n2) {
        nb = dir > 0 ? n + 1 : n;
        na = a1 + (nb - b1) * slope;
      }
      InBand(static_cast<long>(n), pa, pb - n, na, nb - n, sum);
      pa = na, pb = nb;
      if (n == n2) break;
    }
  }

 private:
  int Line(long n) const { return static_cast<int>(((n % lines_) + lines_) % lines_); }
  int Cell(double a) const { return std::clamp(static_cast<int>(std::floor(a)), -1, cells_ - 1); }

  // The band's piece cut at the periods along a (a = -1 + m cells), each moved into the table.
  void InBand(long n, double a1, double t1, double a2, double t2, double* sum) const {
    if (t1 == t2) return;
    // The table holds lines -1 .. lines (the borders wrapped): within them no wrap is needed.
    const bool inside = n >= -1 && n < lines_;
    const int lo = inside ? static_cast<int>(n) : Line(n), hi = inside ? lo + 1 : Line(n + 1);
    if (a1 >= -1 && a1 <= cells_ - 1 && a2 >= -1 && a2 <= cells_ - 1) {
      InPeriod(lo, hi, a1, t1, a2, t2, sum);  // within the first period: no offset
      return;
    }
    const double m1 = std::floor((a1 + 1) / cells_), m2 = std::floor((a2 + 1) / cells_);
    const double dir = m2 >= m1 ? 1 : -1;
    double pa = a1, pt = t1;
    for (double m = m1;; m += dir) {
      double na = a2, nt = t2;
      if (m != m2) {
        na = -1 + (dir > 0 ? m + 1 : m) * cells_;
        nt = t1 + (na - a1) / (a2 - a1) * (t2 - t1);
      }
      const double shift = m * cells_;
      InPeriod(lo, hi, pa - shift, pt, na - shift, nt, sum);
      if (m != 0 && nt != pt) {
        // G_true = G_table + m Gp on both lines: the integral of (1 - t) Gp_n + t Gp_(n+1).
        const double ramp = 0.5 * (nt * nt - pt * pt), flat = nt - pt;
        SummedAreaTable::LineIntegrals plo, phi;
        table_.Line(rows_, lo, cells_ - 2, cells_ - 1, false, &plo);
        table_.Line(rows_, hi, cells_ - 2, cells_ - 1, false, &phi);
        for (int c = 0; c < table_.channels(); ++c)
          sum[c] += m * (plo.g[c] * (flat - ramp) + phi.g[c] * ramp);
      }
      pa = na, pt = nt;
      if (m == m2) break;
    }
  }

  // A piece within one period along a (a in [-1, cells - 1]).
  void InPeriod(int lo, int hi, double a1, double t1, double a2, double t2, double* sum) const {
    if (t1 == t2) return;
    const int m1 = Cell(a1), m2 = Cell(a2);
    if (std::abs(m2 - m1) <= 2) {
      // Cut at the cells' borders; within a cell the integrand is a cubic in the parameter.
      const int dir = m2 >= m1 ? 1 : -1;
      double pa = a1, pt = t1;
      for (int m = m1;; m += dir) {
        double na = a2, nt = t2;
        if (m != m2) {
          na = dir > 0 ? m + 1 : m;
          nt = t1 + (na - a1) / (a2 - a1) * (t2 - t1);
        }
        InCell(lo, hi, Cell(0.5 * (pa + na)), pa, pt, na, nt, sum);
        pa = na, pt = nt;
        if (m == m2) break;
      }
      return;
    }
    // Over many cells: with k = dt / da, the integral is k times that of G_n + t(a) (G_(n+1) -
    // G_n) over a, t(a) = t1 + k (a - a1): the lines' M1 and M2 at both ends.
    const double k = (t2 - t1) / (a2 - a1);
    SummedAreaTable::LineIntegrals e[2][2];  // [line n, n + 1][end 1, 2]
    for (int l = 0; l < 2; ++l) {
      table_.Line(rows_, l == 0 ? lo : hi, m1, a1, true, &e[l][0]);
      table_.Line(rows_, l == 0 ? lo : hi, m2, a2, true, &e[l][1]);
    }
    for (int c = 0; c < table_.channels(); ++c) {
      double d1[2], x[2];  // per line: the integral of G, and of (a - a1) G
      for (int l = 0; l < 2; ++l) {
        d1[l] = e[l][1].m1[c] - e[l][0].m1[c];
        x[l] = (e[l][1].m2[c] - e[l][0].m2[c]) - a1 * d1[l];
      }
      sum[c] += k * ((1 - t1) * d1[0] + t1 * d1[1] + k * (x[1] - x[0]));
    }
  }

  void InCell(int lo, int hi, int m, double a1, double t1, double a2, double t2,
              double* sum) const {
    const double dt = t2 - t1;
    if (dt == 0) return;
    constexpr double kG = 0.28867513459481287;  // 1 / (2 sqrt(3))
    const double ga = a1 + (0.5 - kG) * (a2 - a1), gb = a1 + (0.5 + kG) * (a2 - a1);
    const double ta = t1 + (0.5 - kG) * dt, tb = t1 + (0.5 + kG) * dt;
    double lo_a[4], lo_b[4], hi_a[4], hi_b[4];
    table_.LineAt2(rows_, lo, m, ga, gb, lo_a, lo_b);
    table_.LineAt2(rows_, hi, m, ga, gb, hi_a, hi_b);
    for (int c = 0; c < table_.channels(); ++c)
      sum[c] += 0.5 * dt * ((1 - ta) * lo_a[c] + ta * hi_a[c] + (1 - tb) * lo_b[c] + tb * hi_b[c]);
  }

  const SummedAreaTable& table_;
  bool rows_;
  int cells_, lines_;
};

// The table's corner integral C(x, y) at any point of the repeating texture: with x = p W + r and
// y = q H + s (r, s within the table's first period from -0.5), C = p q C(W, H) + p C(W, s) +
// q C(r, H) + C(r, s), where W and H stand for the period's far end (W - 0.5, H - 0.5).
void PeriodicCorner(const SummedAreaTable& table, double x, double y, double* out) {
  const double w = table.width(), h = table.height();
  const double p = std::floor((x + 0.5) / w), q = std::floor((y + 0.5) / h);
  const double r = x - p * w, s = y - q * h;
  double c[4], cw[4] = {}, ch[4] = {}, all[4] = {};
  table.Corner(r, s, c);
  if (p != 0) table.Corner(w - 0.5, s, cw);
  if (q != 0) table.Corner(r, h - 0.5, ch);
  if (p != 0 && q != 0) table.Corner(w - 0.5, h - 0.5, all);
  for (int k = 0; k < table.channels(); ++k) out[k] = p * q * all[k] + p * cw[k] + q * ch[k] + c[k];
}

// The integral over the polygon (texel units, any position), unless its steps exceed `max_steps`.
bool IntegrateWithin(const SummedAreaTable& table, const TexPoint* v, int n, int max_steps,
                     int* steps, std::array<double, 4>* out) {
  const BandIntegrator rows(table, true), columns(table, false);
  constexpr int kMaxVertices = 16;
  n = std::min(n, kMaxVertices);
  bool by_columns[kMaxVertices];
  // Each edge in its cheaper form, unless one form for all is cheaper still: a vertex where the
  // form changes costs a corner lookup, about two steps (small quads, magnified texels).
  int all_rows = 0, all_columns = 0, mixed = 0, changes = 0;
  for (int e = 0; e < n; ++e) {
    const TexPoint &p = v[e], &q = v[(e + 1) % n];
    const int by_rows = rows.Steps(p.x - 0.5, p.z - 0.5, q.x - 0.5, q.z - 0.5),
              by_cols = columns.Steps(p.z - 0.5, p.x - 0.5, q.z - 0.5, q.x - 0.5);
    by_columns[e] = by_cols < by_rows;
    all_rows += 1 + by_rows, all_columns += 1 + by_cols, mixed += 1 + std::min(by_rows, by_cols);
  }
  for (int e = 0; e < n; ++e) changes += by_columns[e] != by_columns[(e + 1) % n];
  constexpr int kCornerSteps = 2;
  mixed += kCornerSteps * changes;
  *steps = std::min({mixed, all_rows, all_columns});
  if (*steps > max_steps) return false;
  if (*steps != mixed)
    for (int e = 0; e < n; ++e) by_columns[e] = *steps != all_rows;
  double sum[4] = {}, cross[4] = {};
  for (int e = 0; e < n; ++e) {
    const TexPoint &p = v[e], &q = v[(e + 1) % n];
    if (by_columns[e])
      columns.Edge(p.z - 0.5, p.x - 0.5, q.z - 0.5, q.x - 0.5, cross);  // of G dx
    else
      rows.Edge(p.x - 0.5, p.z - 0.5, q.x - 0.5, q.z - 0.5, sum);  // of F dy
  }
  // An edge taken as -G dx adds C(end) - C(start): at a vertex between two such edges the two
  // cancel, so only where the form changes.
  for (int k = 0; k < n; ++k) {
    const bool before = by_columns[(k + n - 1) % n], after = by_columns[k];
    if (before == after) continue;
    double c[4];
    PeriodicCorner(table, v[k].x, v[k].z, c);
    for (int ch = 0; ch < table.channels(); ++ch) sum[ch] += before ? c[ch] : -c[ch];
  }
  *out = {};
  for (int ch = 0; ch < table.channels(); ++ch) (*out)[ch] = sum[ch] - cross[ch];
  return true;
}

}  // namespace

std::array<double, 4> PolygonIntegral(const SummedAreaTable& table, const TexPoint* v, int n) {
  std::array<double, 4> out;
  int steps = 0;
  IntegrateWithin(table, v, n, std::numeric_limits<int>::max(), &steps, &out);
  return out;
}

bool PolygonMean(const std::array<TexPoint, 4>& quad, const SummedAreaTable& table, int max_steps,
                 std::array<double, 4>* mean, int* steps) {
  // The line moments grow with the cube of the line's length: at 4,096 texels their differences
  // keep the mean to about 3e-5
  // (PolygonIntegral.ABilinearPolynomialTextureIsIntegratedAnalytically); wider tables take the
  // fragments.
  constexpr int kMaxSide = 4096;
  if (table.width() > kMaxSide || table.height() > kMaxSide) return false;
  double twice_area = 0;
  if (!Simple(quad, &twice_area) || !(std::abs(twice_area) > 0)) return false;
  // Moved by whole periods next to the origin, in texel units; at most 4,096 periods across (the
  // per-period offsets stay small against the sums).
  double x0 = quad[0].x, x1 = x0, z0 = quad[0].z, z1 = z0;
  for (const TexPoint& p : quad)
    x0 = std::min(x0, p.x), x1 = std::max(x1, p.x), z0 = std::min(z0, p.z), z1 = std::max(z1, p.z);
  if (!(x1 - x0 <= 4096 && z1 - z0 <= 4096)) return false;
  const double sx = std::floor(x0), sz = std::floor(z0), w = table.width(), h = table.height();
  TexPoint v[4];
  for (int k = 0; k < 4; ++k) v[k] = {(quad[k].x - sx) * w, (quad[k].z - sz) * h};
  std::array<double, 4> sum;
  int cost = 0;
  const bool ok = IntegrateWithin(table, v, 4, max_steps, &cost, &sum);
  if (steps != nullptr) *steps = cost;
  if (!ok) return false;
  const double inv = 2.0 / (twice_area * w * h);
  for (int c = 0; c < 4; ++c) (*mean)[c] = sum[c] * inv;
  return true;
}

}  // namespace aperture
