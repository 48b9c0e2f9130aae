#include "support/checker_dome.h"

#include <cmath>

namespace aperture::testing {
namespace {

double Rad(double degrees) { return degrees * M_PI / 180; }
double Deg(double radians) { return radians * 180 / M_PI; }

}  // namespace

v1::Scene CheckerDome() {
  v1::Scene scene;
  scene.set_name("checker dome");
  for (int white = 0; white < 2; ++white) {
    v1::Material& m = *scene.add_materials();
    m.set_id(white ? "white" : "black");
    m.set_unlit(true);
    m.mutable_base_color()->set_r(white);
    m.mutable_base_color()->set_g(white);
    m.mutable_base_color()->set_b(white);
  }
  v1::Mesh& mesh = *scene.add_meshes();
  mesh.set_id("dome");
  mesh.set_material_id("black");
  for (int i = -19; i < 19; ++i)
    for (int j = -6; j < 6; ++j) {
      v1::Polygon& p = *mesh.add_polygons();
      const double a0 = i * kDomeSquareDeg, a1 = a0 + kDomeSquareDeg;
      const double e0 = j * kDomeSquareDeg, e1 = e0 + kDomeSquareDeg;
      p.set_material_id(DomeWhite(a0 + 1, e0 + 1) ? "white" : "black");
      for (const auto& [a, e] : {std::pair{a0, e0}, {a1, e0}, {a1, e1}, {a0, e1}}) {
        const Vec3 d = DomeDirection(a, e) * 1000.0;
        v1::Vec3& v = *p.add_vertices();
        v.set_x(d.x), v.set_y(d.y), v.set_z(d.z);
      }
    }
  scene.add_objects()->set_mesh_id("dome");
  return scene;
}

Vec3 DomeDirection(double azimuth_deg, double elevation_deg) {
  const double a = Rad(azimuth_deg), e = Rad(elevation_deg);
  return {-std::sin(a) * std::cos(e), std::sin(e), -std::cos(a) * std::cos(e)};
}

std::pair<double, double> DomeAngles(const Vec3& d) {
  return {Deg(std::atan2(-d.x, -d.z)), Deg(std::asin(d.y))};
}

bool DomeWhite(double azimuth_deg, double elevation_deg) {
  const auto i = static_cast<long>(std::floor(azimuth_deg / kDomeSquareDeg));
  const auto j = static_cast<long>(std::floor(elevation_deg / kDomeSquareDeg));
  return (i + j) % 2 != 0;
}

bool InsideSquare(double degrees, double margin) {
  return std::abs(std::remainder(degrees, kDomeSquareDeg)) > margin;
}

double AngleBetweenDeg(const Vec3& u, const Vec3& v) {
  // atan2 of the cross and dot products: accurate at tiny angles, where acos is not.
  return Deg(std::atan2(Length(Cross(u, v)), Dot(u, v)));
}

ChannelView::ChannelView(double yaw, const v1::Frustum& f, int w, int h)
    : yaw_deg(yaw),
      left(std::tan(Rad(f.left_deg()))),
      right(std::tan(Rad(f.right_deg()))),
      bottom(std::tan(Rad(f.bottom_deg()))),
      top(std::tan(Rad(f.top_deg()))),
      width(w),
      height(h) {}

namespace {

// Turned about +y by `degrees` (yaw: the view axis (0, 0, -1) goes to (-sin, 0, -cos)).
Vec3 TurnY(const Vec3& v, double degrees) {
  const double c = std::cos(Rad(degrees)), s = std::sin(Rad(degrees));
  return {v.x * c + v.z * s, v.y, -v.x * s + v.z * c};
}
// Turned about +x by `degrees` (pitch: the view axis goes to (0, sin, -cos)).
Vec3 TurnX(const Vec3& v, double degrees) {
  const double c = std::cos(Rad(degrees)), s = std::sin(Rad(degrees));
  return {v.x, v.y * c - v.z * s, v.y * s + v.z * c};
}

}  // namespace

Vec3 ChannelView::At(double x, double y) const {
  const Vec3 r{left + (right - left) * x / width, top - (top - bottom) * y / height, -1};
  return Normalize(TurnY(TurnX(TurnY(r, yaw_deg), eye_pitch_deg), eye_yaw_deg));
}

bool ChannelView::FramePoint(const Vec3& direction, double* x, double* y) const {
  const Vec3 r = TurnY(TurnX(TurnY(direction, -eye_yaw_deg), -eye_pitch_deg), -yaw_deg);
  if (r.z >= 0) return false;
  *x = (r.x / -r.z - left) / (right - left) * width;
  *y = (top - r.y / -r.z) / (top - bottom) * height;
  return true;
}

}  // namespace aperture::testing
