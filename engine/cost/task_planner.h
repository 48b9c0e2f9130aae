// Cuts a frame into the tasks the oneTBB workers run. Uniform: a fixed grid of tiles.
// Cost-driven: windows subdivided Warnock-style until their predicted work (seed 002's filtered
// areas, see window_cost.h) is near a target grain, then ordered most expensive first.
#pragma once

#include <vector>

#include "cost/window_cost.h"
#include "raster/aa_filter.h"
#include "raster/warnock.h"

namespace aperture {

enum class Scheduling { kCost, kUniform };

const char* SchedulingName(Scheduling s);

struct SchedulingOptions {
  Scheduling mode = Scheduling::kCost;
  int uniform_tile = 32;      // kUniform: tile side, pixels
  int tasks_per_thread = 16;  // kCost: the grain is the predicted total over threads x this
  int plan_workers = 0;  // kCost: set the grain for this many threads; 0: the threads rendering
  bool predict_uniform = false;  // kUniform: also predict each tile's cost (for measurements)
  CostModel model = DefaultCostModel();
};

struct TaskWindow {
  PixelRect rect;
  std::vector<int> polygons;  // candidates reaching into the window's apertures
  WindowFeatures features;    // set when the cost is predicted
  double predicted_us = 0;
};

// Deterministic for a given frame and options; `concurrency` only sets the grain.
std::vector<TaskWindow> PlanTasks(const FrameGeometry& geometry, const AaFilterShape& aa,
                                  const PixelRect& region, const SchedulingOptions& options,
                                  int concurrency);

}  // namespace aperture
