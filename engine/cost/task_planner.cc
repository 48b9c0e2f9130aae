#include "cost/task_planner.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "raster/window_quadrants.h"

namespace aperture {
namespace {

constexpr int kRootTile = 64;
// A task at most this wide and high is not split further, whatever its predicted cost: smaller
// tasks would cost more to plan and schedule than they could even out.
constexpr int kSmallestTaskSide = 8;

std::vector<int> Reaching(const FrameGeometry& geo, const std::vector<int>& candidates,
                          const PixelRect& r, double margin) {
  std::vector<int> out;
  for (int i : candidates)
    if (PolygonOverlapsRect(geo.polygons[i], r.x0 - margin, r.y0 - margin, r.x1 + margin,
                            r.y1 + margin))
      out.push_back(i);
  return out;
}

std::vector<TaskWindow> GridTasks(const FrameGeometry& geo, const AaFilterShape& aa,
                                  const PixelRect& region, int tile, const CostModel& model,
                                  bool predict) {
  int cols = 0;
  std::vector<std::vector<int>> bins = BinPolygons(geo, aa.margin, region, tile, &cols);
  std::vector<TaskWindow> tasks(bins.size());
  tbb::parallel_for(size_t{0}, bins.size(), [&](size_t k) {
    const int r = static_cast<int>(k) / cols, c = static_cast<int>(k) % cols;
    TaskWindow& t = tasks[k];
    t.rect = {region.x0 + c * tile, region.y0 + r * tile,
              std::min(region.x1, region.x0 + (c + 1) * tile),
              std::min(region.y1, region.y0 + (r + 1) * tile)};
    t.polygons = Reaching(geo, bins[k], t.rect, aa.margin);
    if (predict) {
      t.features = MeasureWindowFeatures(geo, t.polygons, t.rect, 2 * aa.margin + 1);
      t.predicted_us = model.Predict(t.features);
    }
  });
  return tasks;
}

// Runs of empty root windows along a row become one task: sky is cheap, and many tiny equal
// tasks cost more to schedule than to render. A run ends at the grain, so that on many workers a
// row of sky does not become the frame's longest task.
std::vector<TaskWindow> MergeEmptyRuns(std::vector<TaskWindow> roots, const CostModel& model,
                                       double grain) {
  std::vector<TaskWindow> merged;
  for (TaskWindow& t : roots) {
    if (!merged.empty() && t.polygons.empty() && merged.back().polygons.empty() &&
        merged.back().rect.y0 == t.rect.y0 && merged.back().rect.x1 == t.rect.x0 &&
        merged.back().predicted_us + t.predicted_us <= grain) {
      TaskWindow& run = merged.back();
      run.rect.x1 = t.rect.x1;
      run.features.pixels += t.features.pixels;
      run.predicted_us = model.Predict(run.features);
      continue;
    }
    merged.push_back(std::move(t));
  }
  return merged;
}

void Split(const FrameGeometry& geo, const AaFilterShape& aa, const CostModel& model, double grain,
           TaskWindow window, std::vector<TaskWindow>& out) {
  const WindowQuadrants quads = SplitWindow(window.rect, kSmallestTaskSide);
  if (window.predicted_us <= grain || quads.empty() || window.polygons.empty()) {
    out.push_back(std::move(window));
    return;
  }
  // The quadrants in parallel: a frame's work (and so the planning) gathers in few root windows.
  std::vector<TaskWindow> from_quad[4];
  tbb::parallel_for(0, quads.count, [&](int k) {
    const PixelRect& q = quads.rects[k];
    TaskWindow child;
    child.rect = q;
    child.polygons = Reaching(geo, window.polygons, q, aa.margin);
    child.features = MeasureWindowFeatures(geo, child.polygons, q, 2 * aa.margin + 1);
    child.predicted_us = model.Predict(child.features);
    Split(geo, aa, model, grain, std::move(child), from_quad[k]);
  });
  for (auto& tasks : from_quad)
    for (TaskWindow& t : tasks) out.push_back(std::move(t));
}

}  // namespace

const char* SchedulingName(Scheduling s) { return s == Scheduling::kCost ? "cost" : "uniform"; }

std::vector<TaskWindow> PlanTasks(const FrameGeometry& geo, const AaFilterShape& aa,
                                  const PixelRect& region, const SchedulingOptions& options,
                                  int concurrency) {
  if (options.mode == Scheduling::kUniform)
    return GridTasks(geo, aa, region, std::max(8, options.uniform_tile), options.model,
                     options.predict_uniform);

  std::vector<TaskWindow> roots = GridTasks(geo, aa, region, kRootTile, options.model, true);
  double total = 0;
  for (const TaskWindow& t : roots) total += t.predicted_us;
  const double grain = total / (std::max(1, concurrency) * std::max(1, options.tasks_per_thread));
  roots = MergeEmptyRuns(std::move(roots), options.model, grain);
  std::vector<std::vector<TaskWindow>> per_root(roots.size());
  tbb::parallel_for(size_t{0}, roots.size(), [&](size_t k) {
    Split(geo, aa, options.model, grain, std::move(roots[k]), per_root[k]);
  });
  std::vector<TaskWindow> tasks;
  for (auto& v : per_root)
    for (TaskWindow& t : v) tasks.push_back(std::move(t));
  // Most expensive first (longest-processing-time order); ties keep screen order.
  std::stable_sort(tasks.begin(), tasks.end(), [](const TaskWindow& a, const TaskWindow& b) {
    return a.predicted_us > b.predicted_us;
  });
  return tasks;
}

}  // namespace aperture
