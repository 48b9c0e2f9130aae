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
  const int repeat = argc > 1 ? std::max(1, std::atoi(argv[1])) : 10;
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
  std::printf(
      "1920x1080, box2, trilinear, 2 threads, fastest of %d interleaved rounds; cost model %s\n",
      repeat, StoredCostModelPath().c_str());
  for (const Case& c : cases) {
    // Every round renders once in each mode, so a drifting machine speed favours none of them.
    struct Mode {
      const char* name;
      Scheduling scheduling;
      int tile;
      Run best;
    };
    Mode modes[] = {{"cost-driven", Scheduling::kCost, 0, {}},
                    {"uniform  32px", Scheduling::kUniform, 32, {}},
                    {"uniform  64px", Scheduling::kUniform, 64, {}},
                    {"uniform 128px", Scheduling::kUniform, 128, {}}};
    for (int round = 0; round < repeat; ++round) {
      for (Mode& m : modes) {
        RenderSettings settings;
        settings.threads = 2;
        settings.shading.override_filter = true;
        settings.scheduling.mode = m.scheduling;
        settings.scheduling.uniform_tile = std::max(8, m.tile);
        const Run run = Fastest(*c.scene, c.camera, settings, 1);
        if (run.frame_ms < m.best.frame_ms) m.best = run;
      }
    }
    for (const Mode& m : modes)
      std::printf("%-7s %-14s %7.1f ms, balance %.2f; cost-driven %.2fx faster\n", c.name, m.name,
                  m.best.frame_ms, m.best.efficiency, m.best.frame_ms / modes[0].best.frame_ms);
    std::printf(
        "%-7s Spearman predicted vs measured task time (1 thread): uniform 32px tiles "
        "%.3f, cost-driven tasks %.3f\n",
        c.name, TaskSpearman(*c.scene, c.camera, Scheduling::kUniform, 3),
        TaskSpearman(*c.scene, c.camera, Scheduling::kCost, 3));
  }
  return 0;
}
