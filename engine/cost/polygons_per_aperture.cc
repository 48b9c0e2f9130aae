#include "cost/polygons_per_aperture.h"

#include <cmath>

namespace aperture {
namespace {
constexpr double kPi = 3.14159265358979323846;
}

double PolygonsPerApertureSquare(double kappa, double a, double m, double l_cp, double faces) {
  return kappa + (a / m) * l_cp * std::sqrt(2 * kPi * kappa * faces) + a * a * faces / (m * m);
}

double PolygonsPerApertureCircle(double kappa, double a, double m, double l_cp, double faces) {
  return kappa + (a / m) * l_cp * std::sqrt(kPi * kappa * faces) +
         kPi * a * a * faces / (4 * m * m);
}

double ShapeFactor(double area, double perimeter) {
  return area > 0 ? perimeter / (2 * std::sqrt(kPi * area)) : 0;
}

}  // namespace aperture
