// Fits the window cost model on this machine (`aperture-render --calibrate`): renders calibration
// frames in uniform tiles, times every tile, and fits the model's constants to the times.
#pragma once

#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "cost/window_cost.h"
#include "scene/camera.h"
#include "scene/scene.h"

namespace aperture {

struct CalibrationFrame {
  std::string name;
  const Scene* scene;
  Camera camera;
};

struct CalibrationResult {
  CostModel model;
  int tiles = 0;
  double spearman = 0;  // predicted (with the fitted model) versus measured tile times
};

// Single-threaded, each frame `repeat` times keeping each tile's fastest time.
absl::StatusOr<CalibrationResult> Calibrate(const std::vector<CalibrationFrame>& frames, int width,
                                            int height, int repeat);

}  // namespace aperture
