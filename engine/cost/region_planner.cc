#include "cost/region_planner.h"

#include <algorithm>

#include "cost/task_planner.h"

namespace aperture {

std::vector<FrameRegion> PlanFrameRegions(const FrameGeometry& geometry, const AaFilterShape& aa,
                                          int k, const CostModel& model, int tile) {
  const int width = geometry.width, height = geometry.height;
  k = std::clamp(k, 1, std::max(1, height));

  // Predicted cost per tile (the uniform plan with predictions), spread over the tile's rows.
  SchedulingOptions options;
  options.mode = Scheduling::kUniform;
  options.uniform_tile = tile;
  options.predict_uniform = true;
  options.model = model;
  const std::vector<TaskWindow> tiles =
      PlanTasks(geometry, aa, PixelRect{0, 0, width, height}, options, 1);
  std::vector<double> row_cost(static_cast<size_t>(height), 0.0);
  for (const TaskWindow& t : tiles)
    for (int y = t.rect.y0; y < t.rect.y1; ++y)
      row_cost[static_cast<size_t>(y)] += t.predicted_us / t.rect.height();
  double total = 0;
  for (double c : row_cost) total += c;

  std::vector<FrameRegion> regions;
  int y0 = 0;
  double running = 0;
  for (int j = 1; j <= k; ++j) {
    const double target = total * j / k;
    int y1 = y0;
    double cost = 0;
    // Take rows while the running cost is short of the target, keeping one row for every band
    // still to come (and at least one for this one).
    while (y1 < height - (k - j) &&
           (y1 == y0 || running + row_cost[static_cast<size_t>(y1)] / 2 <= target)) {
      running += row_cost[static_cast<size_t>(y1)];
      cost += row_cost[static_cast<size_t>(y1)];
      ++y1;
    }
    if (j == k) {
      for (; y1 < height; ++y1) cost += row_cost[static_cast<size_t>(y1)];
    }
    regions.push_back({PixelRect{0, y0, width, y1}, cost});
    y0 = y1;
  }
  return regions;
}

}  // namespace aperture
