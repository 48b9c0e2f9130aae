#include "raster/polygon_clip.h"

namespace aperture {
namespace {

template <typename Point, typename Distance>
void ClipGeneric(std::vector<Point>& poly, Distance dist, std::vector<Point>& out) {
  const size_t n = poly.size();
  // Wholly inside (most polygons against most planes): the clip would copy every vertex as it is.
  bool inside = true;
  for (size_t i = 0; i < n; ++i) inside &= dist(poly[i]) >= 0;
  if (inside && n >= 3) return;
  out.clear();
  for (size_t i = 0; i < n; ++i) {
    const Point& p = poly[i];
    const Point& q = poly[i + 1 == n ? 0 : i + 1];
    const double dp = dist(p), dq = dist(q);
    if (dp >= 0) out.push_back(p);
    if ((dp >= 0) != (dq >= 0)) {
      const double t = dp / (dp - dq);
      out.push_back(p + (q - p) * t);
    }
  }
  poly.swap(out);
  if (poly.size() < 3) poly.clear();
}

}  // namespace

void ClipByHalfPlane(std::vector<Vec2>& poly, double a, double b, double c,
                     std::vector<Vec2>& scratch) {
  // Room for every vertex kept and every crossing: the clip never overflows it.
  if (scratch.size() < 2 * poly.size() + 2) scratch.resize(2 * poly.size() + 2);
  const size_t count =
      ClipByHalfPlane(poly.data(), poly.size(), a, b, c, scratch.data(), scratch.size());
  scratch.resize(count);
  poly.swap(scratch);
  if (poly.size() < 3) poly.clear();
}

void ClipToRect(std::vector<Vec2>& poly, double x0, double y0, double x1, double y1,
                std::vector<Vec2>& scratch) {
  if (!poly.empty()) ClipByHalfPlane(poly, 1, 0, -x0, scratch);
  if (!poly.empty()) ClipByHalfPlane(poly, -1, 0, x1, scratch);
  if (!poly.empty()) ClipByHalfPlane(poly, 0, 1, -y0, scratch);
  if (!poly.empty()) ClipByHalfPlane(poly, 0, -1, y1, scratch);
}

void ClipByPlane(std::vector<Vec3>& poly, const Vec3& n, double d, std::vector<Vec3>& scratch) {
  ClipGeneric(
      poly, [&](const Vec3& p) { return Dot(n, p) + d; }, scratch);
}

}  // namespace aperture
