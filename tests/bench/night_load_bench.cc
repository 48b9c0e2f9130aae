// The night scene's load (14 CFR Part 60, Appendix A, Table A1A 6.o: 15,000 visible lights over
// 10,000 visible textured surfaces): what its light points cost Aperture, and what the same frame
// costs Mesa llvmpipe drawing it as a GL image generator does, on 2 threads.
//
// For each of --sizes, the built-in `night` scene from its camera (scene/night_scene.h's
// NightCamera) is rendered three ways: with its light points; without them
// (RenderSettings::draw_light_points false: the same polygons, no light pass); and `night-by-day`
// (the same polygons by day: sun, sky and haze, no lights). Aperture renders on --threads workers
// (RenderFrame's own arena) with --aa edges and the materials' texture filters, as aperture-render
// does; its frame is projection and raster (FrameStats' setup_ms + raster_ms, as aperture-render's
// "frame time"), the light pass (lights_ms) part of the raster. llvmpipe (OSMesa; the script sets
// LP_NUM_THREADS) draws the same polygons from the same camera (scene_gl_peer.h: textured,
// trilinear mip-mapped, lit by each polygon's constant light, into an 8-bit frame, its depth
// range as OpenSceneGraph sets it) at 4x MSAA and 1x, then the lights
// as osgSim's points (scene_peer_points.h: sized per light every frame on the CPU, as osgSim's
// cull does, which its with-lights time includes); its frame runs from the clear to glFinish.
// Every renderer and variant is timed once per round, the rounds interleaved (the first, a
// warm-up, not counted); the tables give medians.
//
// Per size: with lights, without, by day; the lights' cost (with - without) / without; night /
// day (with lights over by day). Aperture's targets: the lights' cost at most 15 %, night at most
// 1.5x day. Exit status 0 when Aperture met both at every size, 3 when not, 1 on an error, 2 on a
// bad flag. The warm-up round's frames go to --out (Aperture's as EXR and PNG, llvmpipe's as PNG).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_split.h"
#include "cost/window_cost.h"
#include "io/exr_writer.h"
#include "light_measure.h"
#include "render/frame_renderer.h"
#include "scene/builtin_scenes.h"
#include "scene/scene_builder.h"
#include "scene_gl_peer.h"
#include "scene_peer_points.h"

namespace aperture {
namespace {

constexpr char kUsage[] = R"(usage: night_load_bench [flags]

The night scene's frame (--scene night, ~25,500 lights in view) with its light points, without
them, and the same polygons by day (night-by-day), Aperture against Mesa llvmpipe drawing the same
frame as a GL image generator does (textured triangles, trilinear, 4x MSAA and 1x, the lights as
osgSim's points), in interleaved rounds; medians, the lights' cost and night / day per renderer.
Run with LP_NUM_THREADS set (scripts/bench-lights.sh load sets 2). Tables on stdout, progress on
stderr. Exit status 0 when Aperture met its targets (lights' cost <= 15 %, night <= 1.5x day) at
every size, 3 when not, 1 on an error, 2 on a bad flag.

  --sizes WxH[,WxH]      frame sizes (default 1280x720,1920x1080)
  --rounds N             timed rounds, after one warm-up round (default 5)
  --threads N            Aperture's worker threads (default 2)
  --aa NAME              Aperture's edge filter: box2, box1 or tent2 (default box2)
  --msaa LIST            llvmpipe's sample counts, of 4 and 1 (default 4,1)
  --peer_min_size PX     osgSim's minimum point size (default 1.5: Aperture's least footprint)
  --peer_texture_side N  the largest side of a texture given to GL (default 8192)
  --peer_near M          llvmpipe's near plane, metres (default 0: as OpenSceneGraph sets it,
                         at least 0.0005 of the far plane, the farthest vertex)
  --encode B             also time the EXR encoding of Aperture's night frame (default true)
  --out DIR              the warm-up round's frames (default out/night-load; empty: none)
  --help                 this text
)";

constexpr double kLightsCostTarget = 0.15;
constexpr double kNightOverDayTarget = 1.5;

struct Options {
  std::vector<std::pair<int, int>> sizes = {{1280, 720}, {1920, 1080}};
  int rounds = 5;
  int threads = 2;
  AntiAliasing aa = AntiAliasing::kBox2;
  std::vector<int> msaa = {4, 1};
  double peer_min_size = 1.5;
  SceneGlPeerOptions peer;
  bool encode = true;
  std::string out = "out/night-load";
};

double NowMs() {
  return std::chrono::duration<double, std::milli>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

// The three frames every renderer draws.
enum Variant { kWithLights, kWithoutLights, kByDay, kVariants };
constexpr const char* kVariantNames[kVariants] = {"night", "night-no-lights", "day"};

// A renderer's times per variant over the rounds, milliseconds.
struct Row {
  std::string name;
  std::vector<double> ms[kVariants];
};

double LightsCost(const Row& row) {
  const double without = Median(row.ms[kWithoutLights]);
  return (Median(row.ms[kWithLights]) - without) / without;
}
double NightOverDay(const Row& row) { return Median(row.ms[kWithLights]) / Median(row.ms[kByDay]); }

// Aperture's figures of one size beside its rows: the light pass, the encode.
struct ApertureDetail {
  std::vector<double> lights_ms, setup_ms, raster_ms, wall_ms, encode_ms;
  size_t lights_drawn = 0, lights_hidden = 0, lights_partly_hidden = 0, visible_polygons = 0;
  int concurrency = 0;
};

// llvmpipe's: the per-frame sizing of the points on the CPU (in its with-lights time), and the
// with-lights frame's GL part alone, per sample count.
struct PeerDetail {
  std::vector<double> points_ms;
  std::vector<std::vector<double>> draw_ms;
  size_t points = 0, lights = 0;
};

absl::Status SaveAperture(const RenderedFrame& frame, const std::string& dir,
                          const std::string& stem) {
  ExrOptions exr;
  if (auto s = WriteExrFile(frame.image, exr, absl::StrCat(dir, "/", stem, ".exr")); !s.ok())
    return s;
  return WritePngPreview(frame.image, absl::StrCat(dir, "/", stem, ".png"));
}

void PrintTable(int width, int height, const std::vector<Row>& rows, int rounds) {
  std::printf(
      "\n%dx%d, medians of %d rounds (ms):\n\n| renderer | with lights | without | by day | "
      "lights' cost | night / day |\n|---|---:|---:|---:|---:|---:|\n",
      width, height, rounds);
  for (const Row& r : rows)
    std::printf("| %s | %.1f | %.1f | %.1f | %.1f %% | %.2fx |\n", r.name.c_str(),
                Median(r.ms[kWithLights]), Median(r.ms[kWithoutLights]), Median(r.ms[kByDay]),
                100 * LightsCost(r), NightOverDay(r));
}

// One size: the rounds, the table, the targets. `met` is cleared when Aperture misses one.
absl::Status RunSize(const Options& o, const Scene& night, const Scene& day, const Camera& camera,
                     SceneGlPeer& peer, int night_peer, int day_peer, int width, int height,
                     bool& met) {
  if (!peer.Resize(width, height))
    return absl::InternalError(absl::StrCat("llvmpipe's buffers of ", width, "x", height));
  RenderSettings settings;
  settings.width = width;
  settings.height = height;
  settings.aa = o.aa;
  settings.threads = o.threads;
  RenderSettings dark = settings;
  dark.draw_light_points = false;

  const std::string size = absl::StrCat(width, "x", height);
  std::vector<Row> rows;
  rows.push_back(
      {absl::StrCat("Aperture ", AntiAliasingName(o.aa), ", frame (projection + raster)"), {}});
  rows.push_back({absl::StrCat("Aperture ", AntiAliasingName(o.aa), ", raster"), {}});
  for (int samples : o.msaa)
    rows.push_back({absl::StrCat("llvmpipe ", samples == 4 ? "4x MSAA" : "1x",
                                 ", trilinear, lights as points"),
                    {}});
  ApertureDetail ap;
  PeerDetail pd;
  pd.draw_ms.resize(o.msaa.size());
  ScenePeerPoints points;
  const bool save = !o.out.empty();
  if (save) {
    std::error_code error;
    std::filesystem::create_directories(o.out, error);
    if (error) return absl::NotFoundError(absl::StrCat("--out ", o.out, ": ", error.message()));
  }

  for (int round = -1; round < o.rounds; ++round) {
    const bool counted = round >= 0;
    // Aperture: with lights, without, by day.
    const Scene* scenes[kVariants] = {&night, &night, &day};
    const RenderSettings* variant_settings[kVariants] = {&settings, &dark, &settings};
    for (int v = 0; v < kVariants; ++v) {
      const double start = NowMs();
      auto frame = RenderFrame(*scenes[v], camera, *variant_settings[v]);
      const double wall = NowMs() - start;
      if (!frame.ok()) return frame.status();
      const FrameStats& s = frame->stats;
      if (counted) {
        rows[0].ms[v].push_back(s.setup_ms + s.raster_ms);
        rows[1].ms[v].push_back(s.raster_ms);
        if (v == kWithLights) {
          ap.lights_ms.push_back(s.lights_ms);
          ap.setup_ms.push_back(s.setup_ms);
          ap.raster_ms.push_back(s.raster_ms);
          ap.wall_ms.push_back(wall);
          ap.lights_drawn = s.lights_drawn;
          ap.lights_hidden = s.lights_hidden;
          ap.lights_partly_hidden = s.lights_partly_hidden;
          ap.visible_polygons = s.visible_polygons;
          ap.concurrency = s.concurrency;
        }
      }
      if (v == kWithLights && o.encode) {
        ExrOptions exr;
        exr.threads = o.threads;
        const double encode_start = NowMs();
        auto bytes = EncodeExr(frame->image, exr);
        const double encode_ms = NowMs() - encode_start;
        if (!bytes.ok()) return bytes.status();
        if (counted) ap.encode_ms.push_back(encode_ms);
      }
      if (!counted && save)
        if (auto st =
                SaveAperture(*frame, o.out, absl::StrCat("aperture-", kVariantNames[v], "-", size));
            !st.ok())
          return st;
    }
    // llvmpipe at each sample count: with lights (their points sized this frame), without, by
    // day.
    for (size_t k = 0; k < o.msaa.size(); ++k) {
      const bool msaa = o.msaa[k] == 4;
      for (int v = 0; v < kVariants; ++v) {
        double ms = 0;
        if (v == kWithLights) {
          const double start = NowMs();
          ScenePeerPointsOf(night, camera, width, height, settings.scene_time_s, o.peer_min_size,
                            points);
          const double points_ms = NowMs() - start;
          const double draw_ms = peer.Draw(night_peer, msaa, &points.points);
          ms = points_ms + draw_ms;
          if (counted) {
            pd.points_ms.push_back(points_ms);
            pd.draw_ms[k].push_back(draw_ms);
            pd.points = points.points.size();
            pd.lights = points.lights;
          }
        } else {
          ms = peer.Draw(v == kByDay ? day_peer : night_peer, msaa, nullptr);
        }
        if (counted) rows[2 + k].ms[v].push_back(ms);
        if (!counted && save)
          if (auto st =
                  WritePngPreview(peer.Read(), absl::StrCat(o.out, "/llvmpipe-", o.msaa[k], "x-",
                                                            kVariantNames[v], "-", size, ".png"));
              !st.ok())
            return st;
      }
    }
    std::fprintf(stderr, "  %s round %d/%d%s\n", size.c_str(), round + 1, o.rounds,
                 counted ? "" : " (warm-up, not counted)");
  }

  PrintTable(width, height, rows, o.rounds);
  std::printf(
      "\nAperture: the light pass %.2f ms of the raster's %.1f (%.1f %% of the frame without "
      "lights); %zu footprints drawn (%zu hidden, %zu partly hidden), %zu polygons visible, %d "
      "threads; "
      "projection %.1f ms; RenderFrame's wall time %.1f ms",
      Median(ap.lights_ms), Median(ap.raster_ms),
      100 * Median(ap.lights_ms) / Median(rows[0].ms[kWithoutLights]), ap.lights_drawn,
      ap.lights_hidden, ap.lights_partly_hidden, ap.visible_polygons, ap.concurrency,
      Median(ap.setup_ms), Median(ap.wall_ms));
  if (!ap.encode_ms.empty())
    std::printf(
        "; the night frame's EXR encoding (half, zip, %d threads) %.1f ms, not in the frame",
        o.threads, Median(ap.encode_ms));
  std::printf(".\n");
  if (!o.msaa.empty()) {
    std::printf(
        "llvmpipe: %zu points for %zu lights, sized on the CPU in %.2f ms a frame (in its "
        "with-lights time); %zu triangles",
        pd.points, pd.lights, Median(pd.points_ms), peer.Triangles(night_peer));
    for (size_t k = 0; k < o.msaa.size(); ++k) {
      const double without = Median(rows[2 + k].ms[kWithoutLights]);
      std::printf("; %dx, GL alone: with lights %.1f ms, the lights' cost %.1f %%", o.msaa[k],
                  Median(pd.draw_ms[k]), 100 * (Median(pd.draw_ms[k]) - without) / without);
    }
    std::printf(".\n");
  }

  const double cost = LightsCost(rows[0]), ratio = NightOverDay(rows[0]);
  const bool cost_met = cost <= kLightsCostTarget, ratio_met = ratio <= kNightOverDayTarget;
  std::printf(
      "targets at %s, Aperture's frame: the lights' cost %.1f %% (at most 15 %%): %s; night / day "
      "%.2fx (at most 1.5x): %s\n",
      size.c_str(), 100 * cost, cost_met ? "met" : "MISSED", ratio, ratio_met ? "met" : "MISSED");
  std::fflush(stdout);
  met = met && cost_met && ratio_met;
  return absl::OkStatus();
}

// ---------------------------------------------------------------------------------------------

bool ParseDouble(const std::string& s, double& out) {
  char* end = nullptr;
  out = std::strtod(s.c_str(), &end);
  return end != s.c_str() && *end == '\0' && std::isfinite(out);
}

bool ParseInt(const std::string& s, int least, int most, int& out) {
  double v = 0;
  if (!ParseDouble(s, v) || v != std::floor(v) || v < least || v > most) return false;
  out = static_cast<int>(v);
  return true;
}

// An error names the flag; `help` is set by --help.
absl::Status ParseOptions(int argc, char** argv, Options& o, bool& help) {
  for (int i = 1; i < argc; i += 2) {
    const std::string flag = argv[i];
    if (flag == "--help" || flag == "-h") {
      help = true;
      return absl::OkStatus();
    }
    if (i + 1 >= argc) return absl::InvalidArgumentError(absl::StrCat(flag, ": needs a value"));
    const std::string value = argv[i + 1];
    auto bad = [&](const char* want) {
      return absl::InvalidArgumentError(absl::StrCat(flag, " ", value, ": ", want));
    };
    if (flag == "--sizes") {
      o.sizes.clear();
      for (absl::string_view part : absl::StrSplit(value, ',', absl::SkipEmpty())) {
        int w = 0, h = 0;
        char rest = 0;
        if (std::sscanf(std::string(part).c_str(), "%dx%d%c", &w, &h, &rest) != 2 || w < 64 ||
            h < 64 || w > 8192 || h > 8192)
          return bad("wants WxH[,WxH], each side 64..8192");
        o.sizes.push_back({w, h});
      }
      if (o.sizes.empty()) return bad("wants WxH[,WxH]");
    } else if (flag == "--rounds") {
      if (!ParseInt(value, 1, 1000, o.rounds)) return bad("wants a whole number in 1..1000");
    } else if (flag == "--threads") {
      if (!ParseInt(value, 1, 1024, o.threads)) return bad("wants a whole number in 1..1024");
    } else if (flag == "--aa") {
      if (value == "box2")
        o.aa = AntiAliasing::kBox2;
      else if (value == "box1")
        o.aa = AntiAliasing::kBox1;
      else if (value == "tent2")
        o.aa = AntiAliasing::kTent2;
      else
        return bad("wants box2, box1 or tent2");
    } else if (flag == "--msaa") {
      o.msaa.clear();
      for (absl::string_view part : absl::StrSplit(value, ',', absl::SkipEmpty())) {
        if (part == "4")
          o.msaa.push_back(4);
        else if (part == "1")
          o.msaa.push_back(1);
        else
          return bad("wants 4 and/or 1, comma separated");
      }
    } else if (flag == "--peer_min_size") {
      if (!ParseDouble(value, o.peer_min_size) || o.peer_min_size < 0 || o.peer_min_size > 30)
        return bad("wants pixels in 0..30");
    } else if (flag == "--peer_texture_side") {
      if (!ParseInt(value, 1, 16384, o.peer.texture_side))
        return bad("wants a whole number in 1..16384");
    } else if (flag == "--peer_near") {
      if (!ParseDouble(value, o.peer.near) || o.peer.near < 0) return bad("wants metres >= 0");
    } else if (flag == "--encode") {
      if (value == "true" || value == "1")
        o.encode = true;
      else if (value == "false" || value == "0")
        o.encode = false;
      else
        return bad("wants true or false");
    } else if (flag == "--out") {
      o.out = value;
    } else {
      return absl::InvalidArgumentError(absl::StrCat("unknown flag ", flag, " (see --help)"));
    }
  }
  return absl::OkStatus();
}

int Run(int argc, char** argv) {
  Options o;
  bool help = false;
  if (auto s = ParseOptions(argc, argv, o, help); !s.ok()) {
    std::fprintf(stderr, "night_load_bench: %s\n", std::string(s.message()).c_str());
    return 2;
  }
  if (help) {
    std::printf("%s", kUsage);
    return 0;
  }
  auto fail = [](const absl::Status& s) {
    std::fprintf(stderr, "night_load_bench: %s\n", std::string(s.message()).c_str());
    return 1;
  };
  // The scenes as every tool builds them (scene/builtin_scenes.h), from the night's camera.
  auto night_proto = FindBuiltinScene("night");
  if (!night_proto.ok()) return fail(night_proto.status());
  auto day_proto = FindBuiltinScene("night-by-day");
  if (!day_proto.ok()) return fail(day_proto.status());
  const Camera camera = night_proto->camera;
  std::fprintf(stderr, "building the night and night-by-day scenes\n");
  auto night = BuildScene(night_proto->scene);
  if (!night.ok()) return fail(night.status());
  auto day = BuildScene(day_proto->scene);
  if (!day.ok()) return fail(day.status());

  SceneGlPeer peer(o.peer);
  if (!peer.Init()) return 1;
  std::fprintf(stderr, "uploading the scenes to llvmpipe\n");
  auto night_peer = peer.AddScene(*night, camera);
  if (!night_peer.ok()) return fail(night_peer.status());
  auto day_peer = peer.AddScene(*day, camera);
  if (!day_peer.ok()) return fail(day_peer.status());

  const char* lp_threads = std::getenv("LP_NUM_THREADS");
  std::printf(
      "night load: the night scene (%zu polygons, %zu light points) from its camera (%.0f degree "
      "vertical field of view, near %g m), Aperture on %d threads against %s (LP_NUM_THREADS=%s; "
      "its vertex stage runs on the calling thread besides those)\n",
      night->polygons.size(), night->lights.lights.size(), camera.vertical_fov_deg, camera.near,
      o.threads, peer.Renderer().c_str(), lp_threads != nullptr ? lp_threads : "unset");
  std::printf("cost model: %s\n", DefaultCostModelSource().c_str());
  std::printf("llvmpipe's textures:\n");
  for (const std::string& note : peer.TextureNotes()) std::printf("  %s\n", note.c_str());
  std::printf("llvmpipe's depth range: near %.1f m, far %.0f m%s\n", peer.Near(*night_peer),
              peer.Far(*night_peer),
              o.peer.near > 0 ? " (--peer_near)"
                              : " (OpenSceneGraph's: far at the farthest vertex, near "
                                "at least 0.0005 of it)");

  bool met = true;
  for (const auto& [w, h] : o.sizes)
    if (auto s = RunSize(o, *night, *day, camera, peer, *night_peer, *day_peer, w, h, met); !s.ok())
      return fail(s);
  if (!o.out.empty()) std::printf("\nframes of the warm-up round in %s\n", o.out.c_str());
  return met ? 0 : 3;
}

}  // namespace
}  // namespace aperture

int main(int argc, char** argv) { return aperture::Run(argc, argv); }
