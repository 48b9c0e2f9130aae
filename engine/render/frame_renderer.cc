#include "render/frame_renderer.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <atomic>
#include <cmath>
#include <optional>

#include "absl/strings/str_cat.h"
#include "base/held_bytes.h"
#include "base/stopwatch.h"
#include "raster/projection.h"
#include "render/frame_memory.h"
#include "render/leaf_renderer.h"
#include "render/light_pass.h"
#include "render/sky_backdrop.h"
#include "render/visible_surfaces.h"

namespace aperture {
namespace {

// What one polygon of the scene costs projected: its ScreenPolygon and the shader's per-polygon
// values (weighed before projection against the frame's budget).
constexpr size_t kProjectedPolygonBytes = sizeof(ScreenPolygon) + 16;

absl::StatusOr<RenderedFrame> RenderInArena(const Scene& scene, const Camera& camera,
                                            const RenderSettings& settings,
                                            const StopRequested& stop) {
  RenderedFrame frame;
  frame.region = settings.region.pixels() > 0 ? settings.region
                                              : PixelRect{0, 0, settings.width, settings.height};
  // What the frame holds against its budget: the image, the projected polygons and the plan are
  // weighed before they are made, the workers' buffers as they grow.
  FrameMemory memory(settings.max_frame_bytes);
  size_t image_held = 0, geometry_held = 0, plan_held = 0;
  const size_t image_bytes =
      static_cast<size_t>(frame.region.width()) * frame.region.height() * sizeof(Rgba);
  if (image_bytes > memory.Room()) {
    memory.Refuse("the image", image_bytes);
    return memory.Error();
  }
  frame.image = Image::Uninitialized(frame.region.width(), frame.region.height());
  memory.Hold(image_held, image_bytes);
  const size_t geometry_bytes = scene.polygons.size() * kProjectedPolygonBytes;
  if (geometry_bytes > memory.Room()) {
    memory.Refuse("the projected polygons", geometry_bytes);
    return memory.Error();
  }
  memory.Hold(geometry_held, geometry_bytes);
  const AaFilterShape shape = ShapeOf(settings.aa);

  Stopwatch timer;
  const FrameGeometry geometry =
      ProjectScene(scene, camera, settings.width, settings.height, shape.margin + 1.0);
  const absl::StatusOr<PolygonShader> made_shader =
      PolygonShader::Create(scene, geometry, settings.shading, stop);
  if (!made_shader.ok()) return made_shader.status();
  const PolygonShader& shader = *made_shader;
  frame.stats.setup_ms = timer.Milliseconds();
  frame.stats.visible_polygons = geometry.polygons.size();

  timer.Restart();
  const int concurrency = tbb::this_task_arena::max_concurrency();
  const int plan_workers =
      settings.scheduling.plan_workers > 0 ? settings.scheduling.plan_workers : concurrency;
  const std::vector<TaskWindow> tasks =
      PlanTasks(geometry, shape, frame.region, settings.scheduling, plan_workers);
  frame.stats.plan_ms = timer.Milliseconds();
  size_t plan_bytes = HeldBytes(tasks);
  for (const TaskWindow& task : tasks) plan_bytes += HeldBytes(task.polygons);
  if (!memory.Hold(plan_held, plan_bytes)) {
    memory.Refuse("the planned tasks' lists of polygons", plan_bytes);
    return memory.Error();
  }
  // Light points: projected first, so that the raster pass keeps what it sees in their cells.
  const Stopwatch lights_timer;
  const std::vector<LightFootprint> footprints =
      settings.draw_light_points ? ProjectLightPoints(scene, camera, geometry, settings)
                                 : std::vector<LightFootprint>{};
  const double project_ms = lights_timer.Milliseconds();
  std::optional<VisibleSurfaces> surfaces;
  size_t surfaces_held = 0;
  if (!footprints.empty()) {
    surfaces.emplace(frame.region, shape.cells_per_axis - 1);
    WantLightCells(footprints, shape, *surfaces);
    if (!memory.Hold(surfaces_held, surfaces->Bytes())) {
      memory.Refuse("the visible polygons kept for the light points", surfaces->Bytes());
      return memory.Error();
    }
  }
  struct Worker {
    LeafRenderer renderer;
    std::vector<LeafWindow> leaves;
    size_t leaves_held = 0;  // what `memory` counts of the leaves' lists
    size_t kinds[3] = {0, 0, 0};
  };
  tbb::enumerable_thread_specific<Worker> workers([&] {
    Worker w{LeafRenderer(geometry, shader, settings.aa, FrameSky(scene, settings), frame.region,
                          stop, &memory),
             {},
             0,
             {}};
    if (surfaces) w.renderer.RecordSurfaces(&*surfaces);
    return w;
  });
  std::vector<double> task_us(tasks.size(), 0);
  // Tasks are taken strictly in plan order (most expensive first for the cost-driven plan).
  std::atomic<size_t> next{0};
  std::atomic<bool> stopped{false};
  tbb::parallel_for(
      0, concurrency,
      [&](int) {
        Worker& w = workers.local();
        for (size_t i = next++; i < tasks.size(); i = next++) {
          if (stopped.load(std::memory_order_relaxed) || (stop && stop())) {
            stopped = true;
            return;
          }
          const Stopwatch task_timer;
          w.leaves.clear();
          SubdivideWindow(geometry, shape, settings.warnock, tasks[i].rect, tasks[i].polygons,
                          w.leaves);
          size_t leaves_bytes = HeldBytes(w.leaves);
          for (const LeafWindow& leaf : w.leaves) leaves_bytes += HeldBytes(leaf.polygons);
          if (!memory.Hold(w.leaves_held, leaves_bytes)) {
            stopped = true;
            return;
          }
          for (const LeafWindow& leaf : w.leaves) {
            // Asked inside a task too, so one long task (a crowded window) does not outlive its
            // deadline; the check itself is throttled by the caller (server/stop_check.h).
            if (!w.renderer.Render(leaf, frame.image) || (stop && stop())) {
              stopped = true;
              return;
            }
            ++w.kinds[static_cast<int>(leaf.kind)];
          }
          task_us[i] = 1000.0 * task_timer.Milliseconds();
        }
      },
      tbb::simple_partitioner());
  if (!stopped && !memory.Exceeded() && SkyByDirection(scene, settings))
    CompositeSky(scene.sky_dome, camera, settings.width, settings.height, frame.region,
                 frame.image);
  if (!stopped && !memory.Exceeded()) {
    LightPassStats lights;
    if (auto s = DrawLightPoints(geometry, settings, frame.region, footprints, frame.image,
                                 surfaces ? &*surfaces : nullptr, &memory, &lights, stop);
        !s.ok())
      return s;
    frame.stats.lights_drawn = lights.drawn;
    frame.stats.lights_hidden = lights.hidden;
    frame.stats.lights_partly_hidden = lights.partly_hidden;
    frame.stats.lights_ms = project_ms + lights.ms;
  }
  frame.stats.raster_ms = timer.Milliseconds();
  if (memory.Exceeded()) return memory.Error();
  if (stopped) {
    size_t done = 0;
    for (double us : task_us) done += us > 0;
    return absl::CancelledError(
        absl::StrCat("frame stopped after ", done, " of ", tasks.size(), " tasks"));
  }
  frame.stats.concurrency = concurrency;
  frame.stats.peak_memory_bytes = memory.Peak();
  for (const Worker& w : workers) {
    frame.stats.empty_leaves += w.kinds[0];
    frame.stats.covered_leaves += w.kinds[1];
    frame.stats.mixed_leaves += w.kinds[2];
  }
  frame.stats.tasks.reserve(tasks.size());
  for (size_t i = 0; i < tasks.size(); ++i)
    frame.stats.tasks.push_back(
        {tasks[i].rect, tasks[i].features, tasks[i].predicted_us, task_us[i]});
  return frame;
}

}  // namespace

absl::StatusOr<RenderedFrame> RenderFrame(const Scene& scene, const Camera& camera,
                                          const RenderSettings& settings,
                                          const StopRequested& stop) {
  if (auto s = ValidateRenderSettings(settings); !s.ok()) return s;
  if (auto s = ValidateCamera(camera); !s.ok()) return s;
  // Spheres and cylinders are seed 003's curved primitives: the Warnock rasterizer draws planar
  // polygons only, and a frame silently missing objects would be wrong, so it refuses.
  if (!scene.curved.empty())
    return absl::InvalidArgumentError(absl::StrCat(
        "the scene has ", scene.curved.size(),
        " sphere(s)/cylinder(s), which only the raytrace mode draws (aperture-render --mode "
        "raytrace; options.mode RENDER_MODE_RAYTRACE in a request); the raster mode renders planar "
        "polygons only"));
  // Memory is bounded by the frame's budget; should the process still run out (other frames,
  // a budget above what the machine has), the frame fails with that error, not the process.
  try {
    if (settings.threads == 0) return RenderInArena(scene, camera, settings, stop);
    tbb::task_arena arena(settings.threads);
    return arena.execute([&] { return RenderInArena(scene, camera, settings, stop); });
  } catch (const std::bad_alloc&) {
    return absl::ResourceExhaustedError(
        "the process ran out of memory while rendering the frame (its budget, --max-frame-mb, "
        "is larger than what the machine has free)");
  }
}

}  // namespace aperture
