// Seed 002's estimate of the mean number of polygons in a filter aperture.
#pragma once

namespace aperture {

// seed 002, eq. 15: square filter base of side a on an image of m x m pixels, relative image
// area kappa, mean shape factor l_cp, F visible faces (an upper bound; equality when all faces
// have equal area).
double PolygonsPerApertureSquare(double kappa, double a, double m, double l_cp, double faces);
// seed 002, eq. 14: circular filter base of diameter a.
double PolygonsPerApertureCircle(double kappa, double a, double m, double l_cp, double faces);

// seed 002, eq. 7: L = 2 l sqrt(pi S), so l = L / (2 sqrt(pi S)); 1 for a circle.
double ShapeFactor(double area, double perimeter);

}  // namespace aperture
