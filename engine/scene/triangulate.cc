#include "scene/triangulate.h"

#include <cmath>

namespace aperture {
namespace {

double Cross(const Vec2& o, const Vec2& a, const Vec2& b) {
  return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
}

bool InsideTriangle(const Vec2& p, const Vec2& a, const Vec2& b, const Vec2& c) {
  return Cross(a, b, p) >= 0 && Cross(b, c, p) >= 0 && Cross(c, a, p) >= 0;
}

}  // namespace

double SignedArea(const std::vector<Vec2>& poly) {
  double area = 0;
  for (size_t i = 0, n = poly.size(); i < n; ++i) {
    const Vec2& a = poly[i];
    const Vec2& b = poly[(i + 1) % n];
    area += a.x * b.y - b.x * a.y;
  }
  return 0.5 * area;
}

bool IsConvex(const std::vector<Vec2>& poly) {
  const size_t n = poly.size();
  const double sign = SignedArea(poly) >= 0 ? 1.0 : -1.0;
  for (size_t i = 0; i < n; ++i) {
    if (sign * Cross(poly[i], poly[(i + 1) % n], poly[(i + 2) % n]) < 0) return false;
  }
  return true;
}

absl::StatusOr<std::vector<std::array<int, 3>>> TriangulateEarClipping(
    const std::vector<Vec2>& input) {
  // Work counter-clockwise.
  std::vector<int> ring(input.size());
  for (size_t i = 0; i < ring.size(); ++i) ring[i] = static_cast<int>(i);
  if (SignedArea(input) < 0) std::reverse(ring.begin(), ring.end());

  std::vector<std::array<int, 3>> triangles;
  size_t guard = 0;
  while (ring.size() > 3) {
    const size_t n = ring.size();
    bool clipped = false;
    for (size_t i = 0; i < n; ++i) {
      const int ia = ring[(i + n - 1) % n], ib = ring[i], ic = ring[(i + 1) % n];
      const Vec2 &a = input[ia], &b = input[ib], &c = input[ic];
      if (Cross(a, b, c) <= 0) continue;  // reflex or collinear: not an ear
      bool blocked = false;
      for (size_t j = 0; j < n && !blocked; ++j) {
        const int k = ring[j];
        if (k == ia || k == ib || k == ic) continue;
        blocked = InsideTriangle(input[k], a, b, c);
      }
      if (blocked) continue;
      triangles.push_back({ia, ib, ic});
      ring.erase(ring.begin() + static_cast<long>(i));
      clipped = true;
      break;
    }
    if (!clipped || ++guard > input.size() * input.size())
      return absl::InvalidArgumentError("polygon is self-intersecting (no ear to clip)");
  }
  if (Cross(input[ring[0]], input[ring[1]], input[ring[2]]) > 0)
    triangles.push_back({ring[0], ring[1], ring[2]});
  return triangles;
}

}  // namespace aperture
