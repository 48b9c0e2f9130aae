// Splits one frame into K regions of equal predicted work, so that K servers render it in about
// the same time. The regions are full-width bands of whole rows, top to bottom: a
// region is a plain sub-rectangle (an EXR data window) and the bands tile the frame exactly.
#pragma once

#include <vector>

#include "cost/window_cost.h"
#include "raster/aa_filter.h"
#include "raster/projection.h"
#include "raster/warnock.h"

namespace aperture {

struct FrameRegion {
  PixelRect rect;
  double predicted_us = 0;  // seed 002's filtered-area cost model (window_cost.h)
};

// 1 <= k <= geometry.height. Each row's predicted cost comes from `tile`-pixel tiles (their
// cost spread evenly over their rows); the bands are cut where the running cost crosses
// j / k of the total.
std::vector<FrameRegion> PlanFrameRegions(const FrameGeometry& geometry, const AaFilterShape& aa,
                                          int k, const CostModel& model, int tile = 16);

}  // namespace aperture
