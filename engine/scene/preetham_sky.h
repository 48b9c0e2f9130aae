// The clear sky's luminance and colour in every direction: A. J. Preetham, P. Shirley and
// B. Smits, "A Practical Analytic Model for Daylight", SIGGRAPH 1999 (Perez et al.'s all-weather
// luminance distribution fitted for luminance Y and chromaticity x, y by turbidity). Brightest
// around the sun and towards the horizon, darkest opposite the sun some way above the horizon.
#pragma once

#include "base/image.h"
#include "scene/vec.h"

namespace aperture {

// Perez's five coefficients of one quantity (A..E of Preetham's eq. 3).
struct PerezCoefficients {
  double a = 0, b = 0, c = 0, d = 0, e = 0;
  // F(theta, gamma) = (1 + A exp(B / cos theta)) (1 + C exp(D gamma) + E cos^2 gamma), theta the
  // view direction's angle from the zenith, gamma its angle from the sun (Preetham eq. 3).
  double F(double cos_theta, double gamma, double cos_gamma) const;
};

class PreethamSky {
 public:
  PreethamSky() = default;
  // `sun`: unit, towards the sun, +y up; the model holds for the sun at or above the horizon
  // (below it, the caller's twilight scale takes over with the sun held on the horizon).
  // `turbidity`: Linke's haze measure the paper fits for 2..10 (2 clear, 3 clear with some
  // haze, 6 warm and moist, 10 hazy).
  PreethamSky(const Vec3& sun, double turbidity);

  // Luminance in kcd/m2 and CIE xy chromaticity towards unit `dir` (+y up); directions below the
  // horizon see the horizon's value.
  void LuminanceXy(const Vec3& dir, double* Y, double* x, double* y) const;
  // Linear Rec. 709 RGB whose luminance is the sky's, in kcd/m2 (alpha 1).
  Rgba Radiance(const Vec3& dir) const;

  double zenith_luminance() const { return zenith_Y_; }
  const Vec3& sun() const { return sun_; }

 private:
  Vec3 sun_{0, 1, 0};
  PerezCoefficients Y_, x_, y_;
  double zenith_Y_ = 0, zenith_x_ = 0, zenith_y_ = 0;
  // Each quantity's zenith value over F(0, theta_s) (Preetham eq. 3's denominator), kept.
  double Y_scale_ = 0, x_scale_ = 0, y_scale_ = 0;
};

// CIE xyY to linear Rec. 709 (sRGB primaries, D65 white) RGB, alpha 1.
Rgba XyYToLinearRgb(double x, double y, double Y);

}  // namespace aperture
