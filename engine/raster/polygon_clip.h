// Clipping of convex polygons by half-planes (Sutherland-Hodgman), in 2D and 3D.
#pragma once

#include <vector>

#include "scene/vec.h"

namespace aperture {

// What the clip below returns when `out` might not hold the result.
inline constexpr size_t kClipOverflow = static_cast<size_t>(-1);

// Keeps the part of in[0, n) where a x + b y + c >= 0, written to `out`, which has room for
// `capacity` vertices; returns its vertex count, which may be below 3 (nothing left), or
// kClipOverflow. A clip of a convex polygon adds at most one vertex, but rounding can make a
// nearly degenerate one cross the line more than twice, so the room is checked as it goes.
// Inline and free of allocation: the exact coverage of a cell clips a few small polygons many
// times. Branch-free: every vertex and every crossing is written, and the count
// advances only past those kept (which side a vertex falls on varies from cell to cell, so
// branches mispredict); the kept values are computed exactly as a branching clip computes them.
inline size_t ClipByHalfPlane(const Vec2* in, size_t n, double a, double b, double c, Vec2* out,
                              size_t capacity) {
  if (n == 0) return 0;
  size_t count = 0;
  double dp = a * in[0].x + b * in[0].y + c;
  for (size_t i = 0; i < n; ++i) {
    if (count + 2 > capacity) return kClipOverflow;  // (never taken in practice: predictable)
    const Vec2& p = in[i];
    const Vec2& q = in[i + 1 == n ? 0 : i + 1];
    const double dq = a * q.x + b * q.y + c;
    out[count] = p;
    count += dp >= 0;
    const double t = dp / (dp - dq);  // unused (maybe not finite) unless the edge crosses
    out[count] = {p.x + (q.x - p.x) * t, p.y + (q.y - p.y) * t};
    count += (dp >= 0) != (dq >= 0);
    dp = dq;
  }
  return count;
}

// Both sides of in[0, n) cut by the line a x + b y + c = 0, in one pass: `inside` gets what
// ClipByHalfPlane(in, n, a, b, c, ...) gives and `outside` what ClipByHalfPlane(in, n, -a, -b,
// -c, ...) gives, bit for bit (negation is exact, so the second's values, crossings and divisions
// are the first's negated, and the crossing points the same). Each has room for `capacity`
// vertices; false (counts undefined) when one might not fit.
inline bool SplitByLine(const Vec2* in, size_t n, double a, double b, double c, Vec2* inside,
                        size_t& in_count, Vec2* outside, size_t& out_count, size_t capacity) {
  in_count = out_count = 0;
  if (n == 0) return true;
  double dp = a * in[0].x + b * in[0].y + c;
  for (size_t i = 0; i < n; ++i) {
    if (in_count + 2 > capacity || out_count + 2 > capacity) return false;
    const Vec2& p = in[i];
    const Vec2& q = in[i + 1 == n ? 0 : i + 1];
    const double dq = a * q.x + b * q.y + c;
    const double t = dp / (dp - dq);  // unused (maybe not finite) unless the edge crosses
    const Vec2 cross{p.x + (q.x - p.x) * t, p.y + (q.y - p.y) * t};
    inside[in_count] = p;
    in_count += dp >= 0;
    inside[in_count] = cross;
    in_count += (dp >= 0) != (dq >= 0);
    outside[out_count] = p;
    out_count += dp <= 0;
    outside[out_count] = cross;
    out_count += (dp <= 0) != (dq <= 0);
    dp = dq;
  }
  return true;
}

// Keeps the part where a x + b y + c >= 0 (emptied when fewer than 3 vertices are left).
void ClipByHalfPlane(std::vector<Vec2>& polygon, double a, double b, double c,
                     std::vector<Vec2>& scratch);
// Keeps the part inside [x0, x1] x [y0, y1].
void ClipToRect(std::vector<Vec2>& polygon, double x0, double y0, double x1, double y1,
                std::vector<Vec2>& scratch);
// Keeps the part where dot(n, p) + d >= 0.
void ClipByPlane(std::vector<Vec3>& polygon, const Vec3& n, double d, std::vector<Vec3>& scratch);

}  // namespace aperture
