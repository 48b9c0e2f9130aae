// A plot of per-row figures as an image (aperture-bench filter's per-row PSNR): one polyline per
// series over the rows, grid lines every 10 units, no text (the caller says which colour is which).
#pragma once

#include <vector>

#include "base/image.h"

namespace aperture {

struct PlotSeries {
  std::vector<double> values;  // one per row; not finite: no point there
  Rgba colour;
};

// `width` x `height` pixels, white; x spans the rows [first, values.size()), y the range of the
// finite values rounded out to multiples of 10.
Image PlotRows(const std::vector<PlotSeries>& series, int first, int width, int height);

}  // namespace aperture
