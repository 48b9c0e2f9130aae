// aperture-render: renders one frame locally and writes it as OpenEXR (plus a PNG preview).
#include <spdlog/cfg/env.h>
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>

#include "absl/flags/flag.h"
#include "absl/flags/parse.h"
#include "absl/flags/usage.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "absl/strings/str_join.h"
#include "base/stopwatch.h"
#include "cli_usage.h"
#include "cost/frame_statistics.h"
#include "cost/window_cost.h"
#include "flag_names.h"
#include "frame/camera_proto.h"
#include "frame/frame_job.h"
#include "frame/render_frame_job.h"
#include "frame_flags.h"
#include "gltf_import.h"
#include "io/exr_writer.h"
#include "large_buffers.h"
#include "render/frame_memory.h"
#include "render/trace_renderer.h"
#include "scene/benchmark_scenes.h"
#include "scene/builtin_scenes.h"
#include "scene/demo_scene.h"
#include "scene/scene_builder.h"
#include "scene/scene_file.h"
#include "scene/scene_update.h"
#include "store/shared_store.h"
#include "tools/calibration.h"

// The frame's flags (--scene, --camera, --size, --aa, --filter, --mode, -o, ...) are the client's:
// common/frame_flags.h. These are aperture-render's own.
ABSL_FLAG(std::string, store, aperture::kDefaultStoreDirectory,
          "the machine's shared texture store (the server's default): seed 000 tables, decoded "
          "packed textures and raytrace tables are mapped from it, or built once and kept there "
          "for the next process; 'none': build them in this process only");
ABSL_FLAG(int, zip_level, 4,
          "deflate level of zip and zips compression (libdeflate), 1 (fastest) .. 9 (smallest)");
ABSL_FLAG(bool, preview, true, "also write an sRGB PNG preview next to the EXR");
ABSL_FLAG(int, threads, 0, "worker threads (0: all cores)");
ABSL_FLAG(uint64_t, max_frame_mb, 0,
          "working memory the frame may hold (projected polygons, planned tasks, the workers' "
          "cell buffers, the image), MiB; past it the frame stops with an error; 0: a quarter of "
          "the machine's memory");
ABSL_FLAG(int, repeat, 1, "render this many times and report the fastest (for benchmarks)");
ABSL_FLAG(int, exact_steps, aperture::FragmentOptions{}.exact_steps,
          "raytrace: a pixel's projection is integrated exactly (by its edges against the "
          "summed-area table) when that takes at most this many row or column steps, else by seed "
          "003's fragments within --delta (where their work cap misses it, by a coarser mip "
          "level's exact integral); 0: fragments for every pixel, as the paper does");
ABSL_FLAG(int, leaf, aperture::WarnockOptions{}.leaf_size,
          "largest Warnock leaf window, pixels (of a window few polygons reach)");
ABSL_FLAG(int, crowded_leaf, aperture::WarnockOptions{}.crowded_leaf_size,
          "largest Warnock leaf window that more than 8 polygons reach, pixels");
ABSL_FLAG(std::string, scheduling, "cost",
          "task planning: cost (seed 002 cost-driven windows, most expensive first) or uniform "
          "(fixed tiles)");
ABSL_FLAG(int, tile, 32, "tile side for --scheduling uniform, pixels");
ABSL_FLAG(bool, calibrate, false,
          "fit the tile cost model on this machine (demo, skewed and triangle scenes, one thread) "
          "and store it in --cost-model; renders nothing else");
ABSL_FLAG(std::string, cost_model, "",
          "the tile cost model file: read for the frame, written by --calibrate (default: "
          "$APERTURE_COST_MODEL, else share/aperture/cost_model.txt of this installation, beside "
          "its bin/)");
ABSL_FLAG(bool, stats, false,
          "print seed 002's frame statistics (F, kappa, l_cp), its predicted polygons per "
          "aperture and the measured mean");

namespace aperture {
namespace {

int Fail(const absl::Status& status) {
  std::fprintf(stderr, "aperture-render: error: %s\n", std::string(status.message()).c_str());
  return 2;
}

void PrintStatistics(const Scene& scene, const Camera& camera, const RenderSettings& settings) {
  const double a = settings.aa == AntiAliasing::kBox1 ? 1.0 : 2.0;
  const FrameGeometry geo = ProjectScene(scene, camera, settings.width, settings.height, a);
  const FrameStatistics s = ComputeFrameStatistics(geo, a);
  std::printf("seed 002 statistics (a = %g): F = %d faces, kappa = %.4f, l_cp = %.3f, m = %.1f\n",
              a, s.faces, s.kappa, s.mean_shape_factor, s.image_side);
  std::printf("polygons per aperture: predicted n_square = %.4f, n_circle = %.4f; measured %.4f\n",
              s.predicted_square, s.predicted_circle, MeasurePolygonsPerAperture(geo, a));
}

// This process's own choices for the frame (aperture-render's flags, not the request's).
absl::StatusOr<FrameJobOptions> FrameJobOptionsFromFlags() {
  FrameJobOptions local;
  local.threads = absl::GetFlag(FLAGS_threads);
  local.max_frame_bytes = absl::GetFlag(FLAGS_max_frame_mb) > 0
                              ? absl::GetFlag(FLAGS_max_frame_mb) << 20
                              : DefaultFrameBudgetBytes();
  local.warnock.leaf_size = absl::GetFlag(FLAGS_leaf);
  local.warnock.crowded_leaf_size = absl::GetFlag(FLAGS_crowded_leaf);
  if (const std::string mode = absl::GetFlag(FLAGS_scheduling); mode == "uniform") {
    local.scheduling = Scheduling::kUniform;
  } else if (mode != "cost") {
    return absl::InvalidArgumentError("unknown scheduling '" + mode + "' (cost, uniform)");
  }
  local.uniform_tile = absl::GetFlag(FLAGS_tile);
  local.zip_level = absl::GetFlag(FLAGS_zip_level);
  local.exact_steps = std::max(0, absl::GetFlag(FLAGS_exact_steps));  // below 0: as 0
  return local;
}

int RunCalibration() {
  auto demo = BuildScene(MakeDemoScene());
  auto skewed = BuildScene(MakeSkewedCityScene());
  auto triangles = BuildScene(MakeTriangleFieldScene(3000));
  if (!demo.ok() || !skewed.ok() || !triangles.ok()) return Fail(demo.status());
  const Camera origin{.position = {0, 0, 0}};
  std::printf("calibrating the tile cost model (3 scenes at 960x540, 32-pixel tiles, 1 thread)\n");
  auto result = Calibrate({{"demo", &*demo, DemoCamera()},
                           {"skewed", &*skewed, origin},
                           {"triangles", &*triangles, origin}},
                          960, 540, 3);
  if (!result.ok()) return Fail(result.status());
  std::string path = absl::GetFlag(FLAGS_cost_model);
  if (path.empty()) path = CostModelSearchPath().front();
  std::error_code error;
  if (const auto folder = std::filesystem::path(path).parent_path(); !folder.empty())
    std::filesystem::create_directories(folder, error);
  if (auto s = SaveCostModel(result->model, path); !s.ok()) return Fail(s);
  std::printf(
      "%d tiles: per_pixel %.4g us, per_area %.4g us, per_boundary %.4g us; Spearman "
      "predicted vs measured %.3f\nstored in %s\n",
      result->tiles, result->model.per_pixel, result->model.per_area, result->model.per_boundary,
      result->spearman, path.c_str());
  return 0;
}

int Run() {
  if (absl::GetFlag(FLAGS_calibrate)) return RunCalibration();
  // Options first, so that a mistake is reported before any work is done.
  if (const std::string path = absl::GetFlag(FLAGS_cost_model); !path.empty())
    if (auto s = UseCostModelFile(path); !s.ok()) return Fail(s);
  const std::string scene_arg = absl::GetFlag(FLAGS_scene);
  // A built-in scene by name (scene/builtin_scenes.h) comes with its camera; else a file.
  auto builtin = FindBuiltinScene(scene_arg);
  if (!builtin.ok() && NamesCountedBuiltinScene(scene_arg)) return Fail(builtin.status());
  std::optional<v1::Camera> own_camera;
  if (builtin.ok()) own_camera = CameraToProto(builtin->camera);
  // A glTF model is read here, once: its cameras (by name, the first by default) are options.
  std::vector<GltfCamera> model_cameras;
  std::optional<v1::Scene> model;
  if (!builtin.ok() && IsGltfPath(scene_arg)) {
    auto read = ReadSceneFile(scene_arg, &model_cameras);
    if (!read.ok()) return Fail(read.status());
    model = *std::move(read);
  }
  // The flags become the request a client would send, and the request the engine's job, as on
  // the server: the same flags render the same frame here and through the service.
  bool both_modes = false;
  auto request = FrameRequestFromFlags(own_camera, model_cameras, &both_modes);
  if (!request.ok()) return Fail(request.status());
  auto local = FrameJobOptionsFromFlags();
  if (!local.ok()) return Fail(local.status());
  auto job = FrameJobFromRequest(*request, *local);
  if (!job.ok()) return Fail(job.status());
  const Camera& camera = job->camera;
  const RenderSettings& settings = job->settings;
  ExrOptions& exr = job->exr;
  // "both": raster, then raytrace, on the same scene in one run (to compare the two modes).
  const std::vector<bool> raytrace_modes =
      both_modes ? std::vector<bool>{false, true} : std::vector<bool>{job->mode.raytrace};
  const TraceOptions& trace_options = job->mode.trace;

  // The shared store, so that a one-frame job maps what an earlier process built. A store that
  // cannot be opened (no /dev/shm, no permission) is not fatal: the tables are built here.
  std::shared_ptr<SharedStore> store;
  if (const std::string dir = absl::GetFlag(FLAGS_store); dir != "none") {
    auto opened = SharedStore::Open(dir);
    if (opened.ok())
      store = *opened;
    else
      std::fprintf(stderr, "aperture-render: warning: store %s not used: %s\n", dir.c_str(),
                   std::string(opened.status().message()).c_str());
  }
  SceneBuildOptions build_options;
  build_options.store = store;
  auto built = builtin.ok() ? BuildScene(builtin->scene, build_options)
               : model      ? BuildSceneFile(*model, scene_arg, store)
                            : LoadSceneFile(scene_arg, store);
  if (!built.ok()) return Fail(built.status());
  if (built->name.empty()) built->name = scene_arg;
  // The request's form of the scene is not needed once it is built (tris-1000000: 0.4 GB).
  if (builtin.ok()) v1::Scene().Swap(&builtin->scene);
  if (model) model.reset();
  // The request's update (--time, --place) applies as the server applies a frame's.
  if (request->has_update())
    if (auto s = ApplySceneUpdate(request->update(), &*built); !s.ok()) return Fail(s);
  if (built->time_of_day && built->time_of_day->utc) {
    const SceneTimeOfDay& t = *built->time_of_day;
    const SunPosition sun = SunPositionAt(*t.utc, t.place);
    std::printf("time of day %s at %.4f, %.4f: sun altitude %.2f deg, azimuth %.2f deg (%s)\n",
                absl::FormatTime("%Y-%m-%dT%H:%M:%SZ", *t.utc, absl::UTCTimeZone()).c_str(),
                t.place.latitude_deg, t.place.longitude_deg, sun.altitude_deg, sun.azimuth_deg,
                PhaseName(PhaseOf(sun.altitude_deg)));
  }

  double raster_ms = 0, raytrace_ms = 0;
  for (const bool raytrace : raytrace_modes) {
    FrameJob mode_job = *job;
    mode_job.mode.raytrace = raytrace;
    // The scene's ray-tracing state, built once (and timed) for all of this mode's frames.
    std::shared_ptr<const TracedScene> traced;
    if (raytrace) {
      const Stopwatch build_timer;
      auto ts = TracedScene::Build(*built, store);
      if (!ts.ok()) return Fail(ts.status());
      traced = std::move(*ts);
      std::printf("raytrace: Embree BVH of %zu triangles and summed-area tables in %.1f ms\n",
                  traced->rays().triangles(), build_timer.Milliseconds());
    }
    const TracedSceneSource traced_source =
        [&]() -> absl::StatusOr<std::shared_ptr<const TracedScene>> { return traced; };

    // With both modes, --repeat is for the raster frame; the raytraced one renders once.
    const int repeat =
        raytrace_modes.size() > 1 && traced ? 1 : std::max(1, absl::GetFlag(FLAGS_repeat));
    absl::StatusOr<RenderedFrame> best;
    TraceStats trace_stats;
    for (int i = 0; i < repeat; ++i) {
      TraceStats frame_trace;
      auto frame = RenderFrameJob(*built, mode_job, traced_source, {}, &frame_trace);
      if (!frame.ok()) return Fail(frame.status());
      const auto total = [](const RenderedFrame& f) {
        return f.stats.setup_ms + f.stats.raster_ms;
      };
      if (!best.ok() || total(*frame) < total(*best)) {
        best = std::move(frame);
        trace_stats = frame_trace;
      }
    }
    const FrameStats& stats = best->stats;

    exr.metadata = FrameJobMetadata(built->name, mode_job, *best);
    std::string out = absl::GetFlag(FLAGS_o);
    if (raytrace_modes.size() > 1 && traced) {  // both: the raytraced frame next to the raster one
      std::filesystem::path path(out);
      out = (path.parent_path() / (path.stem().string() + "-raytrace" + path.extension().string()))
                .string();
    }
    double encode_ms = 0;
    for (int i = 0; i < repeat; ++i) {
      const Stopwatch encode_timer;
      if (auto s = WriteExrFile(best->image, exr, out); !s.ok()) return Fail(s);
      const double ms = encode_timer.Milliseconds();
      encode_ms = i == 0 ? ms : std::min(encode_ms, ms);
    }
    std::string preview;
    if (absl::GetFlag(FLAGS_preview)) {
      preview = std::filesystem::path(out).replace_extension(".png").string();
      if (auto s = WritePngPreview(best->image, preview); !s.ok()) return Fail(s);
    }
    if (traced) {
      const TraceStats& t = trace_stats;
      std::printf(
          "%s: %dx%d raytrace on %d threads: %zu corner rays in %.2f ms (%.2f M rays/s), %zu "
          "pixels subdivided with %zu more rays\n",
          built->name.c_str(), settings.width, settings.height, stats.concurrency, t.corner_rays,
          t.corner_ms, t.corner_ms > 0 ? t.corner_rays / (1000.0 * t.corner_ms) : 0.0,
          t.subdivided_pixels, t.extra_rays);
      const FragmentStats& f = t.fragments;
      std::printf(
          "projections: %.1f %% exact by their edges (%.1f steps each, at most %d; %.1f %% of all "
          "on "
          "a coarser mip level, %.1f levels up, where the fragments miss delta), the rest by "
          "fragments: %.1f per projection (delta %g); mean S_fragments / S_quad - 1 = %.4f over "
          "those by edges (0) or fragments, %.4f over those by fragments\n",
          100 * f.ExactShare(), f.exact > 0 ? f.exact_steps / f.exact : 0.0,
          trace_options.fragments.exact_steps, 100 * f.Share(f.coarse),
          f.coarse > 0 ? f.coarse_level_sum / f.coarse : 0.0,
          f.quads > 0 ? f.fragments / f.quads : 0.0, trace_options.fragments.delta,
          f.MeanRelativeError(), f.FragmentMeanRelativeError());
      std::printf("frame time: corner rays %.2f ms, pixels %.2f ms, encode %.2f ms (%s, %s)%s\n",
                  t.corner_ms, t.shade_ms, encode_ms, ExrCompressionName(exr.compression),
                  exr.pixel_type == ExrPixelType::kHalf ? "half" : "float",
                  repeat > 1 ? absl::StrFormat(" [fastest of %d]", repeat).c_str() : "");
    } else {
      std::printf("%s: %dx%d, %zu polygons visible, leaves %zu empty / %zu covered / %zu mixed\n",
                  built->name.c_str(), settings.width, settings.height, stats.visible_polygons,
                  stats.empty_leaves, stats.covered_leaves, stats.mixed_leaves);
      std::printf("%zu %s tasks on %d threads, balance efficiency %.2f\n", stats.tasks.size(),
                  SchedulingName(settings.scheduling.mode), stats.concurrency,
                  stats.BalanceEfficiency());
      std::printf("cost model: %s\n", DefaultCostModelSource().c_str());
      if (stats.lights_drawn > 0)
        std::printf(
            "light points: %zu footprints drawn (%zu hidden, %zu partly hidden) in %.2f ms\n",
            stats.lights_drawn, stats.lights_hidden, stats.lights_partly_hidden, stats.lights_ms);
      std::printf("working memory: %.1f MiB at most (budget %.0f MiB)\n",
                  stats.peak_memory_bytes / 1048576.0, settings.max_frame_bytes / 1048576.0);
      std::printf(
          "frame time: setup %.2f ms, raster %.2f ms (planning %.2f), encode %.2f ms (%s, %s)%s\n",
          stats.setup_ms, stats.raster_ms, stats.plan_ms, encode_ms,
          ExrCompressionName(exr.compression),
          exr.pixel_type == ExrPixelType::kHalf ? "half" : "float",
          repeat > 1 ? absl::StrFormat(" [fastest of %d]", repeat).c_str() : "");
    }
    std::printf("wrote %s%s%s\n", out.c_str(), preview.empty() ? "" : " and ", preview.c_str());
    (traced ? raytrace_ms : raster_ms) = stats.setup_ms + stats.raster_ms;
  }
  if (raytrace_modes.size() > 1)
    std::printf("raster %.1f ms, raytrace %.1f ms: raytrace takes %.1fx the raster frame\n",
                raster_ms, raytrace_ms, raster_ms > 0 ? raytrace_ms / raster_ms : 0.0);
  if (absl::GetFlag(FLAGS_stats)) PrintStatistics(*built, camera, settings);
  if (store) {
    const StoreCounters c = store->counters();
    std::printf("store %s: %llu entries mapped, %llu built here\n",
                absl::GetFlag(FLAGS_store).c_str(), static_cast<unsigned long long>(c.attached),
                static_cast<unsigned long long>(c.built));
  }
  return 0;
}

}  // namespace
}  // namespace aperture

int main(int argc, char** argv) {
  aperture::HandleHelpAndVersion(
      argc, argv, "aperture-render",
      "renders one frame locally.\n  aperture-render --scene NAME|FILE.json|MODEL.glb --camera "
      "X,Y,Z,YAW,PITCH,ROLL --fov 60 --size 1920x1080 --aa box2 -o frame.exr");
  aperture::DashedFlagNames args(argc, argv);
  // Engine log lines (tables built, stores opened) on stderr, stdout kept for the frame's report;
  // the level from SPDLOG_LEVEL (e.g. SPDLOG_LEVEL=warn).
  spdlog::set_default_logger(spdlog::stderr_color_mt("aperture-render"));
  spdlog::cfg::load_env_levels();  // --zip-level as --zip_level
  absl::ParseCommandLine(args.argc(), args.argv());
  aperture::KeepLargeBuffersWarm();  // --repeat's frames reuse warm buffers, as the server's do
  return aperture::Run();
}
