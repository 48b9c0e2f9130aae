#include "trace/curved_intersect.h"

#include <algorithm>
#include <cmath>

namespace aperture {
namespace {

// The roots of a t^2 + 2 b t + c = 0 (a > 0), t0 <= t1, by the cancellation-free form; false when
// the ray misses.
bool SolveQuadratic(double a, double b, double c, double* t0, double* t1) {
  const double disc = b * b - a * c;
  if (!(disc >= 0) || !(a > 0)) return false;
  const double q = -(b + std::copysign(std::sqrt(disc), b));
  if (q == 0) {
    *t0 = *t1 = 0;
    return true;
  }
  *t0 = q / a;
  *t1 = c / q;
  if (*t0 > *t1) std::swap(*t0, *t1);
  return true;
}

// Keeps the candidate when it is nearer than the best so far and inside the segment.
void Consider(double t, CurvedPart part, double t_near, double t_far, double* best_t,
              CurvedPart* best_part, bool* found) {
  if (t > t_near && t <= t_far && (!*found || t < *best_t)) {
    *best_t = t;
    *best_part = part;
    *found = true;
  }
}

}  // namespace

std::optional<CurvedHit> IntersectCurved(const CurvedPrimitive& c, const Vec3& origin,
                                         const Vec3& dir, double t_near, double t_far) {
  // In the primitive's frame: o, d = axes^T (origin - c.origin), axes^T dir.
  const Mat3 to_local = c.axes.Transposed();
  const Vec3 o = to_local * (origin - c.origin), d = to_local * dir;
  double best_t = 0;
  CurvedPart part = CurvedPart::kOutside;
  bool found = false;
  if (c.kind == CurvedKind::kSphere) {
    // |o + t d|^2 = r^2: the entering root sees the outside, the leaving one the inside.
    double t0, t1;
    if (SolveQuadratic(Dot(d, d), Dot(o, d), Dot(o, o) - c.radius * c.radius, &t0, &t1)) {
      Consider(t0, CurvedPart::kOutside, t_near, t_far, &best_t, &part, &found);
      Consider(t1, CurvedPart::kInside, t_near, t_far, &best_t, &part, &found);
    }
  } else {
    // The side: (o + t d)_x^2 + (o + t d)_z^2 = r^2 with 0 <= y <= height.
    double t0, t1;
    const double a = d.x * d.x + d.z * d.z;
    if (SolveQuadratic(a, o.x * d.x + o.z * d.z, o.x * o.x + o.z * o.z - c.radius * c.radius, &t0,
                       &t1)) {
      const double y0 = o.y + t0 * d.y, y1 = o.y + t1 * d.y;
      if (y0 >= 0 && y0 <= c.height)
        Consider(t0, CurvedPart::kOutside, t_near, t_far, &best_t, &part, &found);
      if (y1 >= 0 && y1 <= c.height)
        Consider(t1, CurvedPart::kInside, t_near, t_far, &best_t, &part, &found);
    }
    // The caps: the planes y = 0 and y = height within the radius.
    if (c.capped && d.y != 0) {
      const double r2 = c.radius * c.radius;
      for (const double plane : {0.0, c.height}) {
        const double t = (plane - o.y) / d.y;
        const double x = o.x + t * d.x, z = o.z + t * d.z;
        if (x * x + z * z <= r2)
          Consider(t, plane == 0 ? CurvedPart::kBottomCap : CurvedPart::kTopCap, t_near, t_far,
                   &best_t, &part, &found);
      }
    }
  }
  if (!found) return std::nullopt;
  CurvedHit hit;
  hit.t = best_t;
  hit.part = part;
  hit.point = origin + dir * best_t;
  const Vec3 p = o + d * best_t;  // local
  Vec3 n;
  switch (part) {
    case CurvedPart::kOutside:
    case CurvedPart::kInside:
      n = c.kind == CurvedKind::kSphere ? p * (1.0 / c.radius) : Vec3{p.x, 0, p.z};
      break;
    case CurvedPart::kBottomCap:
      n = {0, -1, 0};
      break;
    case CurvedPart::kTopCap:
      n = {0, 1, 0};
      break;
  }
  hit.normal = Normalize(c.axes * n);
  return hit;
}

void CurvedBounds(const CurvedPrimitive& c, Vec3* lo, Vec3* hi) {
  if (c.kind == CurvedKind::kSphere) {
    const Vec3 r{c.radius, c.radius, c.radius};
    *lo = c.origin - r;
    *hi = c.origin + r;
    return;
  }
  // A cylinder's box: its two discs', each extending r sqrt(1 - a_i^2) along world axis i.
  const Vec3 axis{c.axes.m[0][1], c.axes.m[1][1], c.axes.m[2][1]};
  const Vec3 e{c.radius * std::sqrt(std::max(0.0, 1 - axis.x * axis.x)),
               c.radius * std::sqrt(std::max(0.0, 1 - axis.y * axis.y)),
               c.radius * std::sqrt(std::max(0.0, 1 - axis.z * axis.z))};
  const Vec3 top = c.origin + axis * c.height;
  *lo = {std::min(c.origin.x, top.x) - e.x, std::min(c.origin.y, top.y) - e.y,
         std::min(c.origin.z, top.z) - e.z};
  *hi = {std::max(c.origin.x, top.x) + e.x, std::max(c.origin.y, top.y) + e.y,
         std::max(c.origin.z, top.z) + e.z};
}

}  // namespace aperture
