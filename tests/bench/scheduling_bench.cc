// Load-balancing benchmark (issue 6): per scene, cost-driven versus uniform tiles at 1920x1080
// with 2 threads in one run (frame time, balance efficiency), and how well the cost model ranks
// the tiles (Spearman, predicted versus measured 32-pixel tile times on one thread).
// Usage: scheduling_bench [REPEAT]
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "cost/rank_correlation.h"
#include "render/frame_renderer.h"
#include "scene/benchmark_scenes.h"
#include "scene/demo_scene.h"
#include "scene/scene_builder.h"

namespace aperture {
namespace {

struct Run {
  double frame_ms = 1e300, efficiency = 0;
};

Run Fastest(const Scene& scene, const Camera& camera, RenderSettings settings, int repeat) {
  Run best;
  for (int i = 0; i < repeat; ++i) {
    auto frame = RenderFrame(scene, camera, settings);
    if (!frame.ok()) std::exit(1);
    const double ms = frame->stats.setup_ms + frame->stats.raster_ms;
    if (ms < best.frame_ms) best = {ms, frame->stats.BalanceEfficiency()};
  }
  return best;
}

double TaskSpearman(const Scene& scene, const Camera& camera, Scheduling mode, int repeat) {
  RenderSettings settings;
  settings.threads = 1;
  settings.shading.override_filter = true;
  settings.scheduling.mode = mode;
  settings.scheduling.predict_uniform = true;
  std::vector<double> predicted, measured;
  for (int i = 0; i < repeat; ++i) {
    auto frame = RenderFrame(scene, camera, settings);
    if (!frame.ok()) std::exit(1);
    if (measured.empty()) measured.assign(frame->stats.tasks.size(), 1e300);
    predicted.clear();
    for (size_t k = 0; k < frame->stats.tasks.size(); ++k) {
      predicted.push_back(frame->stats.tasks[k].predicted_us);
      measured[k] = std::min(measured[k], frame->stats.tasks[k].measured_us);
    }
  }
  return SpearmanCorrelation(predicted, measured);
}

}  // namespace
}  // namespace aperture

int main(int argc, char** argv) {
  using namespace aperture;
  const int repeat = argc > 1 ? std::max(1, std::atoi(argv[1])) : 5;
  auto demo = BuildScene(MakeDemoScene());
  auto skewed = BuildScene(MakeSkewedCityScene());
  if (!demo.ok() || !skewed.ok()) return 1;
  Camera demo_camera = DemoCamera();
  const Camera origin{.position = {0, 0, 0}};
  struct Case {
    const char* name;
    const Scene* scene;
    Camera camera;
  };
  const Case cases[] = {{"demo", &*demo, demo_camera}, {"skewed", &*skewed, origin}};
  std::printf("1920x1080, box2, trilinear, 2 threads, fastest of %d; cost model %s\n", repeat,
              StoredCostModelPath().c_str());
  for (const Case& c : cases) {
    RenderSettings settings;
    settings.threads = 2;
    settings.shading.override_filter = true;
    settings.scheduling.mode = Scheduling::kCost;
    const Run cost = Fastest(*c.scene, c.camera, settings, repeat);
    std::printf("%-7s cost-driven: %7.1f ms, balance %.2f\n", c.name, cost.frame_ms,
                cost.efficiency);
    settings.scheduling.mode = Scheduling::kUniform;
    for (int tile : {32, 64, 128}) {
      settings.scheduling.uniform_tile = tile;
      const Run uniform = Fastest(*c.scene, c.camera, settings, repeat);
      std::printf("%-7s uniform %3dpx: %7.1f ms, balance %.2f; cost-driven is %.2fx faster\n",
                  c.name, tile, uniform.frame_ms, uniform.efficiency,
                  uniform.frame_ms / cost.frame_ms);
    }
    std::printf(
        "%-7s Spearman predicted vs measured task time (1 thread): uniform 32px tiles "
        "%.3f, cost-driven tasks %.3f\n",
        c.name, TaskSpearman(*c.scene, c.camera, Scheduling::kUniform, 3),
        TaskSpearman(*c.scene, c.camera, Scheduling::kCost, 3));
  }
  return 0;
}
