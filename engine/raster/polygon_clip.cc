#include "raster/polygon_clip.h"

namespace aperture {
namespace {

template <typename Point, typename Distance>
void ClipGeneric(std::vector<Point>& poly, Distance dist, std::vector<Point>& out) {
  out.clear();
  const size_t n = poly.size();
  for (size_t i = 0; i < n; ++i) {
    const Point& p = poly[i];
    const Point& q = poly[(i + 1) % n];
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

struct V2 {  // Vec2 with the arithmetic ClipGeneric needs
  static Vec2 Lerp(const Vec2& p, const Vec2& q, double t) {
    return {p.x + (q.x - p.x) * t, p.y + (q.y - p.y) * t};
  }
};

}  // namespace

void ClipByHalfPlane(std::vector<Vec2>& poly, double a, double b, double c,
                     std::vector<Vec2>& scratch) {
  scratch.clear();
  const size_t n = poly.size();
  for (size_t i = 0; i < n; ++i) {
    const Vec2& p = poly[i];
    const Vec2& q = poly[(i + 1) % n];
    const double dp = a * p.x + b * p.y + c, dq = a * q.x + b * q.y + c;
    if (dp >= 0) scratch.push_back(p);
    if ((dp >= 0) != (dq >= 0)) scratch.push_back(V2::Lerp(p, q, dp / (dp - dq)));
  }
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
