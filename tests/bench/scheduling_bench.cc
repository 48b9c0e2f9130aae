// Load-balancing benchmark: per scene, cost-driven versus uniform tiles at 1920x1080
// with 2 threads in one run (frame time, balance efficiency), and how well the cost model ranks
// the tiles (Spearman, predicted versus measured 32-pixel tile times on one thread), and every plan
// replayed on more workers than this machine has (task times measured on one thread, dispatched
// as the renderer dispatches them; testing/dispatch_replay.h).
// Usage: scheduling_bench [REPEAT]
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <iterator>
#include <string>
#include <vector>

#include "cost/rank_correlation.h"
#include "render/frame_renderer.h"
#include "scene/benchmark_scenes.h"
#include "scene/demo_scene.h"
#include "scene/scene_builder.h"
#include "testing/dispatch_replay.h"

namespace aperture {
namespace {

struct Run {
  double frame_ms = 1e300, efficiency = 0;
};

// The bench's frames: box2 edges, every material trilinear.
RenderSettings BenchSettings(int threads, Scheduling mode, int tile = 32, int plan_workers = 0) {
  RenderSettings settings;
  settings.threads = threads;
  settings.shading.override_filter = true;
  settings.scheduling.mode = mode;
  settings.scheduling.uniform_tile = std::max(8, tile);
  settings.scheduling.plan_workers = plan_workers;
  return settings;
}

RenderedFrame RenderOrExit(const Scene& scene, const Camera& camera,
                           const RenderSettings& settings) {
  auto frame = RenderFrame(scene, camera, settings);
  if (!frame.ok()) {
    std::fprintf(stderr, "scheduling_bench: %s\n", frame.status().ToString().c_str());
    std::exit(1);
  }
  return *std::move(frame);
}

Run Fastest(const Scene& scene, const Camera& camera, RenderSettings settings, int repeat) {
  Run best;
  for (int i = 0; i < repeat; ++i) {
    const RenderedFrame frame = RenderOrExit(scene, camera, settings);
    const double ms = frame.stats.setup_ms + frame.stats.raster_ms;
    if (ms < best.frame_ms) best = {ms, frame.stats.BalanceEfficiency()};
  }
  return best;
}

double TaskSpearman(const Scene& scene, const Camera& camera, Scheduling mode, int repeat) {
  RenderSettings settings = BenchSettings(1, mode);
  settings.scheduling.predict_uniform = true;
  std::vector<double> predicted, measured;
  for (int i = 0; i < repeat; ++i) {
    const RenderedFrame frame = RenderOrExit(scene, camera, settings);
    if (measured.empty()) measured.assign(frame.stats.tasks.size(), 1e300);
    predicted.clear();
    for (size_t k = 0; k < frame.stats.tasks.size(); ++k) {
      predicted.push_back(frame.stats.tasks[k].predicted_us);
      measured[k] = std::min(measured[k], frame.stats.tasks[k].measured_us);
    }
  }
  return SpearmanCorrelation(predicted, measured);
}

// One plan whose task times are measured on one thread for the replay.
struct ReplayPlan {
  Scheduling mode;
  int tile = 32;                // kUniform
  int plan_workers = 0;         // kCost: the worker count the plan is made for
  std::vector<double> task_us;  // of the round with the fastest frame, in plan order
  double frame_us = 1e300;      // that round's raster time
};

// Every plan's makespan on 2..32 workers. The cost-driven plan is made for each worker count
// (its grain depends on it); uniform tiles are the same at every count. Each round renders every
// plan once, so a slow spell of the machine costs all plans alike. A plan's task times are those
// of its fastest frame: the fastest time of each task on its own would favour fine plans, whose
// many small tasks each get more chances to miss the machine's slow moments.
void PrintReplay(const char* name, const Scene& scene, const Camera& camera, int rounds) {
  const int worker_counts[] = {2, 4, 8, 16, 32};
  std::vector<ReplayPlan> plans = {{Scheduling::kUniform, 32, 0, {}},
                                   {Scheduling::kUniform, 64, 0, {}},
                                   {Scheduling::kUniform, 128, 0, {}}};
  for (int workers : worker_counts) plans.push_back({Scheduling::kCost, 32, workers, {}});
  for (int round = 0; round < rounds; ++round) {
    for (ReplayPlan& plan : plans) {
      const RenderedFrame frame =
          RenderOrExit(scene, camera, BenchSettings(1, plan.mode, plan.tile, plan.plan_workers));
      if (frame.stats.raster_ms * 1000 >= plan.frame_us) continue;
      plan.frame_us = frame.stats.raster_ms * 1000;
      plan.task_us.clear();
      for (const TaskTiming& t : frame.stats.tasks) plan.task_us.push_back(t.measured_us);
    }
  }
  std::printf(
      "%-7s replay: task times on 1 thread (fastest frame of %d rounds) dispatched in plan order "
      "to N "
      "workers; makespan ms (balance)\n",
      name, rounds);
  std::printf(
      "%-7s workers  cost-driven     uniform 32px    uniform 64px    uniform 128px   "
      "best uniform / cost\n",
      name);
  auto cell = [](const std::vector<double>& tasks, int workers) {
    double busy = 0;
    for (double t : tasks) busy += t;
    const double makespan_ms = ReplayDispatch(tasks, workers) / 1000;
    std::printf("%7.2f (%.2f)  ", makespan_ms, busy / 1000 / (workers * makespan_ms));
    return makespan_ms;
  };
  for (size_t w = 0; w < std::size(worker_counts); ++w) {
    const int workers = worker_counts[w];
    std::printf("%-7s %7d  ", name, workers);
    const double cost_ms = cell(plans[3 + w].task_us, workers);
    double best_uniform_ms = 1e300;
    for (int t = 0; t < 3; ++t)
      best_uniform_ms = std::min(best_uniform_ms, cell(plans[t].task_us, workers));
    std::printf("%.2fx\n", best_uniform_ms / cost_ms);
  }
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
      repeat, DefaultCostModelSource().c_str());
  for (const Case& c : cases) {
    // Every round renders once in each mode, so a drifting machine speed favours none of them.
    struct Mode {
      const char* name;
      Scheduling scheduling;
      int tile;
      Run best;
      std::vector<double> ms;  // every round's frame time
    };
    Mode modes[] = {{"cost-driven", Scheduling::kCost, 0, {}, {}},
                    {"uniform  32px", Scheduling::kUniform, 32, {}, {}},
                    {"uniform  64px", Scheduling::kUniform, 64, {}, {}},
                    {"uniform 128px", Scheduling::kUniform, 128, {}, {}}};
    for (int round = 0; round < repeat; ++round) {
      for (Mode& m : modes) {
        const Run run = Fastest(*c.scene, c.camera, BenchSettings(2, m.scheduling, m.tile), 1);
        m.ms.push_back(run.frame_ms);
        if (run.frame_ms < m.best.frame_ms) m.best = run;
      }
    }
    // Each round's uniform / cost-driven ratio pairs runs made moments apart; the median of those
    // and how many rounds the cost-driven plan won say more on a noisy machine than the minima.
    for (const Mode& m : modes) {
      std::vector<double> ratios;
      int wins = 0;
      for (int round = 0; round < repeat; ++round) {
        ratios.push_back(m.ms[round] / modes[0].ms[round]);
        wins += modes[0].ms[round] < m.ms[round];
      }
      std::nth_element(ratios.begin(), ratios.begin() + ratios.size() / 2, ratios.end());
      std::printf("%-7s %-14s %7.1f ms, balance %.2f; cost-driven %.3fx faster", c.name, m.name,
                  m.best.frame_ms, m.best.efficiency, m.best.frame_ms / modes[0].best.frame_ms);
      if (&m != &modes[0])
        std::printf(" (paired rounds: median %.3fx, won %d of %d)", ratios[ratios.size() / 2], wins,
                    repeat);
      std::printf("\n");
    }
    std::printf(
        "%-7s Spearman predicted vs measured task time (1 thread): uniform 32px tiles "
        "%.3f, cost-driven tasks %.3f\n",
        c.name, TaskSpearman(*c.scene, c.camera, Scheduling::kUniform, 3),
        TaskSpearman(*c.scene, c.camera, Scheduling::kCost, 3));
    PrintReplay(c.name, *c.scene, c.camera, std::max(3, repeat));
  }
  return 0;
}
