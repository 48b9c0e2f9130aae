#include "trace/texture_mapping.h"

#include <algorithm>
#include <cmath>

namespace aperture {

Affine2 Affine2::ScaleRotateShift(double sx, double sz, double angle_deg, double shift_x,
                                  double shift_z) {
  const double r = Radians(angle_deg), cs = std::cos(r), sn = std::sin(r);
  return {cs * sx, -sn * sz, sn * sx, cs * sz, shift_x, shift_z};
}

TexPoint F1(const PrimitiveMapping& m, const Vec3& world_point) {
  const Vec3 p = m.axes.Transposed() * (world_point - m.origin);
  switch (m.kind) {
    case MappingKind::kLinear:
      return {Dot(m.su, p), Dot(m.sv, p)};
    case MappingKind::kCylindrical:
    case MappingKind::kSpherical: {
      double x = std::atan2(p.x, p.z) / (2 * kPi);
      if (x < 0) x += 1;
      if (m.kind == MappingKind::kCylindrical) return {x, p.y / m.height};
      const double r = Length(p);
      return {x, r > 0 ? std::acos(std::clamp(p.y / r, -1.0, 1.0)) / kPi : 0.0};
    }
    case MappingKind::kDisc:
      return {0.5 * (p.x / m.radius + 1), 0.5 * (p.z / m.radius + 1)};
  }
  return {};
}

std::array<TexPoint, 4> MapQuad(const PrimitiveMapping& m, const std::array<Vec3, 4>& points) {
  std::array<TexPoint, 4> q;
  for (int k = 0; k < 4; ++k) q[k] = F1(m, points[k]);
  return UnwrapAndTransform(m, q);
}

PrimitiveMapping CurvedMapping(const CurvedPrimitive& c, bool cap) {
  PrimitiveMapping m;
  m.kind = cap                               ? MappingKind::kDisc
           : c.kind == CurvedKind::kCylinder ? MappingKind::kCylindrical
                                             : MappingKind::kSpherical;
  m.origin = c.origin;
  m.axes = c.axes;
  m.height = c.height;
  m.radius = c.radius;
  const TextureAffine& t = c.texture;
  m.f2 = {t.a, t.b, t.c, t.d, t.e, t.f};
  return m;
}

std::array<TexPoint, 4> UnwrapAndTransform(const PrimitiveMapping& m, std::array<TexPoint, 4> q) {
  if (m.kind == MappingKind::kCylindrical || m.kind == MappingKind::kSpherical)
    for (int k = 1; k < 4; ++k) q[k].x -= std::round(q[k].x - q[0].x);  // the seam
  for (TexPoint& p : q) p = m.f2.Apply(p);  // seed 003, eq. 2: F = F2(F1(P))
  return q;
}

}  // namespace aperture
