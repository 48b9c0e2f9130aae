// Small double-precision vector types for scene setup (world and camera space).
#pragma once

#include <cmath>

namespace aperture {

struct Vec2 {
  double x = 0, y = 0;
};

struct Vec3 {
  double x = 0, y = 0, z = 0;

  Vec3 operator+(const Vec3& o) const { return {x + o.x, y + o.y, z + o.z}; }
  Vec3 operator-(const Vec3& o) const { return {x - o.x, y - o.y, z - o.z}; }
  Vec3 operator*(double s) const { return {x * s, y * s, z * s}; }
  Vec3 operator-() const { return {-x, -y, -z}; }
  bool operator==(const Vec3&) const = default;
};

inline double Dot(const Vec3& a, const Vec3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline Vec3 Cross(const Vec3& a, const Vec3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline double Length(const Vec3& a) { return std::sqrt(Dot(a, a)); }
inline Vec3 Normalize(const Vec3& a) {
  double len = Length(a);
  return len > 0 ? a * (1.0 / len) : a;
}
inline bool IsFinite(const Vec3& a) {
  return std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(a.z);
}

// Row-major 3x3 rotation/scale matrix.
struct Mat3 {
  double m[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};

  Vec3 operator*(const Vec3& v) const {
    return {m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z,
            m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
            m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z};
  }
  Mat3 operator*(const Mat3& o) const {
    Mat3 r;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        r.m[i][j] = m[i][0] * o.m[0][j] + m[i][1] * o.m[1][j] + m[i][2] * o.m[2][j];
    return r;
  }
  Mat3 Transposed() const {
    Mat3 r;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) r.m[i][j] = m[j][i];
    return r;
  }
  static Mat3 Scale(const Vec3& s) {
    Mat3 r;
    r.m[0][0] = s.x;
    r.m[1][1] = s.y;
    r.m[2][2] = s.z;
    return r;
  }
};

constexpr double kPi = 3.14159265358979323846;
inline double Radians(double deg) { return deg * (kPi / 180.0); }

// Rotation for yaw, then pitch, then roll (DESIGN.md conventions): yaw about +y, pitch about the
// (yawed) right axis, roll about the view axis; positive roll turns the image counter-clockwise,
// i.e. the body rotates clockwise about its -z view axis.
inline Mat3 YawPitchRoll(double yaw_deg, double pitch_deg, double roll_deg) {
  double cy = std::cos(Radians(yaw_deg)), sy = std::sin(Radians(yaw_deg));
  double cp = std::cos(Radians(pitch_deg)), sp = std::sin(Radians(pitch_deg));
  double cr = std::cos(Radians(-roll_deg)), sr = std::sin(Radians(-roll_deg));
  Mat3 yaw, pitch, roll;
  yaw.m[0][0] = cy, yaw.m[0][2] = sy, yaw.m[2][0] = -sy, yaw.m[2][2] = cy;
  pitch.m[1][1] = cp, pitch.m[1][2] = -sp, pitch.m[2][1] = sp, pitch.m[2][2] = cp;
  roll.m[0][0] = cr, roll.m[0][1] = -sr, roll.m[1][0] = sr, roll.m[1][1] = cr;
  return yaw * pitch * roll;
}

}  // namespace aperture
