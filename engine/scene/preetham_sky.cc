#include "scene/preetham_sky.h"

#include <algorithm>
#include <cmath>

namespace aperture {
namespace {

// Views this close to the horizon (cos theta) are held there: F's exp(B / cos theta) is the
// model's horizon brightening and would be undefined at cos theta = 0.
constexpr double kMinCosTheta = 0.01;

// Preetham's appendix A.2: Perez coefficients for Y, x and y, linear in turbidity T.
PerezCoefficients LuminanceCoefficients(double t) {
  return {0.1787 * t - 1.4630, -0.3554 * t + 0.4275, -0.0227 * t + 5.3251, 0.1206 * t - 2.5771,
          -0.0670 * t + 0.3703};
}
PerezCoefficients XCoefficients(double t) {
  return {-0.0193 * t - 0.2592, -0.0665 * t + 0.0008, -0.0004 * t + 0.2125, -0.0641 * t - 0.8989,
          -0.0033 * t + 0.0452};
}
PerezCoefficients YCoefficients(double t) {
  return {-0.0167 * t - 0.2608, -0.0950 * t + 0.0092, -0.0079 * t + 0.2102, -0.0441 * t - 1.6537,
          -0.0109 * t + 0.0529};
}

// Preetham's appendix A.2: the zenith chromaticity, [T^2 T 1] M [theta_s^3 theta_s^2 theta_s 1]^T.
double ZenithChromaticity(const double m[3][4], double t, double theta_s) {
  const double tv[3] = {t * t, t, 1};
  const double sv[4] = {theta_s * theta_s * theta_s, theta_s * theta_s, theta_s, 1};
  double sum = 0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 4; ++j) sum += tv[i] * m[i][j] * sv[j];
  return sum;
}

constexpr double kZenithX[3][4] = {{0.00166, -0.00375, 0.00209, 0},
                                   {-0.02903, 0.06377, -0.03202, 0.00394},
                                   {0.11693, -0.21196, 0.06052, 0.25886}};
constexpr double kZenithY[3][4] = {{0.00275, -0.00610, 0.00317, 0},
                                   {-0.04214, 0.08970, -0.04153, 0.00516},
                                   {0.15346, -0.26756, 0.06670, 0.26688}};

}  // namespace

double PerezCoefficients::F(double cos_theta, double gamma, double cos_gamma) const {
  return (1 + a * std::exp(b / cos_theta)) *
         (1 + c * std::exp(d * gamma) + e * cos_gamma * cos_gamma);
}

PreethamSky::PreethamSky(const Vec3& sun, double turbidity) : sun_(Normalize(sun)) {
  const double t = turbidity;
  const double cos_s = std::clamp(sun_.y, 0.0, 1.0);
  const double theta_s = std::acos(cos_s);
  Y_ = LuminanceCoefficients(t);
  x_ = XCoefficients(t);
  y_ = YCoefficients(t);
  // Preetham's appendix A.2: zenith luminance in kcd/m2, chi = (4/9 - T/120)(pi - 2 theta_s).
  const double chi = (4.0 / 9.0 - t / 120.0) * (kPi - 2 * theta_s);
  zenith_Y_ = (4.0453 * t - 4.9710) * std::tan(chi) - 0.2155 * t + 2.4192;
  zenith_x_ = ZenithChromaticity(kZenithX, t, theta_s);
  zenith_y_ = ZenithChromaticity(kZenithY, t, theta_s);
  // At the zenith theta = 0 and gamma = theta_s.
  Y_scale_ = zenith_Y_ / Y_.F(1, theta_s, cos_s);
  x_scale_ = zenith_x_ / x_.F(1, theta_s, cos_s);
  y_scale_ = zenith_y_ / y_.F(1, theta_s, cos_s);
}

void PreethamSky::LuminanceXy(const Vec3& dir, double* Y, double* x, double* y) const {
  const double cos_theta = std::max(dir.y, kMinCosTheta);
  // The angle to the sun of the direction held at the horizon, as F's theta is.
  const Vec3 held = dir.y >= kMinCosTheta ? dir : Normalize({dir.x, 0, dir.z});
  const double cos_gamma = std::clamp(Dot(held, sun_), -1.0, 1.0);
  const double gamma = std::acos(cos_gamma);
  *Y = Y_scale_ * Y_.F(cos_theta, gamma, cos_gamma);
  *x = x_scale_ * x_.F(cos_theta, gamma, cos_gamma);
  *y = y_scale_ * y_.F(cos_theta, gamma, cos_gamma);
}

Rgba PreethamSky::Radiance(const Vec3& dir) const {
  double Y = 0, x = 0, y = 0;
  LuminanceXy(dir, &Y, &x, &y);
  return XyYToLinearRgb(x, y, Y);
}

Rgba XyYToLinearRgb(double x, double y, double Y) {
  if (y <= 0 || Y <= 0) return {0, 0, 0, 1};
  const double X = x / y * Y, Z = (1 - x - y) / y * Y;
  // IEC 61966-2-1 (sRGB): XYZ to linear RGB.
  const double r = 3.2406 * X - 1.5372 * Y - 0.4986 * Z;
  const double g = -0.9689 * X + 1.8758 * Y + 0.0415 * Z;
  const double b = 0.0557 * X - 0.2040 * Y + 1.0570 * Z;
  return {static_cast<float>(std::max(0.0, r)), static_cast<float>(std::max(0.0, g)),
          static_cast<float>(std::max(0.0, b)), 1};
}

}  // namespace aperture
