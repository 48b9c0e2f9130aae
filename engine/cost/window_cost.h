// Predicted work of a screen window: seed 002's filtered area of each polygon reaching
// into it, S + a L / sqrt(2) + a^2 per vertex, clipped to the window, plus a per-pixel base.
// The constants are fitted on the machine by `aperture-render --calibrate`.
#pragma once

#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "raster/projection.h"
#include "raster/warnock.h"

namespace aperture {

// What a window's cost is predicted from.
struct WindowFeatures {
  double pixels = 0;
  double area = 0;      // sum over polygons of S clipped to the window, pixels
  double boundary = 0;  // sum of a L / sqrt(2) + a^2 V: edge length (and vertices) in the window
  int polygons = 0;
};

// cost (microseconds) = per_pixel pixels + per_area area + per_boundary boundary.
struct CostModel {
  double per_pixel = 0.0007;
  double per_area = 0.047;
  double per_boundary = 0.137;

  double Predict(const WindowFeatures& f) const {
    return per_pixel * f.pixels + per_area * f.area + per_boundary * f.boundary;
  }
};

// `polygons`: candidates (indices into geometry.polygons); `a`: the edge filter's aperture.
WindowFeatures MeasureWindowFeatures(const FrameGeometry& geometry,
                                     const std::vector<int>& polygons, const PixelRect& rect,
                                     double a);

// Least-squares fit of the three constants (kept non-negative) to measured window times.
CostModel FitCostModel(const std::vector<WindowFeatures>& features,
                       const std::vector<double>& microseconds);

// "per_pixel per_area per_boundary" in a text file.
absl::StatusOr<CostModel> LoadCostModel(const std::string& path);
absl::Status SaveCostModel(const CostModel& model, const std::string& path);

// Where the calibrated model is looked for, first found first: $APERTURE_COST_MODEL; the
// installation's share/aperture/cost_model.txt beside the running program's bin/ (so an install
// prefix, a .deb or a container image can be moved); the same under the prefix it was built for
// (CMAKE_INSTALL_PREFIX). `aperture-render --calibrate` writes the first of them (or its
// --cost-model); a build tree is a prefix too (build/share/aperture/).
std::vector<std::string> CostModelSearchPath();

// Makes the model in `path` the process's (aperture-server --cost-model): an error names the
// file when it is missing or malformed, and nothing changes then.
absl::Status UseCostModelFile(const std::string& path);

// The process's model: the one UseCostModelFile set, else the first stored model on the search
// path (read once per process), else the defaults above (fitted on a 2-core x86-64 machine).
CostModel DefaultCostModel();
// Where DefaultCostModel's model came from: a path, or "built-in defaults".
std::string DefaultCostModelSource();

}  // namespace aperture
