// Statistics of a projected frame that seed 002's estimate needs, and the measured count it
// predicts. Faces are the projected polygons clipped to the image (occlusion is not subtracted,
// as for the paper's translucent scenes, so kappa may exceed 1).
#pragma once

#include <vector>

#include "raster/projection.h"

namespace aperture {

struct FaceStatistics {
  int polygon;          // index into the frame's polygons
  double area;          // S_i, pixels
  double perimeter;     // L_i, pixels
  double shape_factor;  // l_i, seed 002 eq. 7
};

struct FrameStatistics {
  int faces = 0;                 // F
  double image_side = 0;         // m = sqrt(W H)
  double kappa = 0;              // S_sum / m^2
  double mean_shape_factor = 0;  // l_cp = sum l_i sqrt(S_i) / sum sqrt(S_i)
  double aperture = 2;           // a
  double predicted_square = 0;   // n_square, eq. 15
  double predicted_circle = 0;   // n_circle, eq. 14
  std::vector<FaceStatistics> per_face;
};

FrameStatistics ComputeFrameStatistics(const FrameGeometry& geometry, double aperture);

// The mean over pixels of the number of polygons reaching into the pixel's a x a square
// aperture (centred on the pixel centre): what n_square predicts. Exact, by testing every pixel
// in each polygon's bounding box.
double MeasurePolygonsPerAperture(const FrameGeometry& geometry, double aperture);

}  // namespace aperture
