// Do light points blink? (FAA Part 60's acceptance of a simulator's visual system: light points
// must not blink or crawl as they move across the screen.) Aperture against Mesa llvmpipe
// drawing the same lights as OpenSceneGraph-based image generators do (osgSim: smooth GL points,
// light_point_peer.h), on the same frames, each light's energy measured from the images.
//
//   blink   A slow approach: the 3 degree glide path at --speed m/s, --fps frames a second for
//           --frames frames, towards a runway lit by rows of lights (--scene; the default,
//           `runway`, is support/runway_lights_scene.h's: edge, centre line, threshold, end,
//           approach row and crossbar, 266 lights), at each of --sizes. Every frame, every
//           steady light's energy is isolated exactly (light_measure.h says how: Aperture renders
//           the light's window with that light alone and without it), through each --aa filter;
//           llvmpipe draws the light's points alone into the same window, 1x and 4x MSAA, with
//           each of --peer_min_sizes as osgSim's minimum point size (1.5 px: Aperture's least
//           footprint; 0: osgSim's default, sub-pixel points faded by alpha). A light's energy is
//           divided by its analytic energy, exposure x I T / d^2 / (one pixel's solid angle)
//           with I its lobe's intensity towards the eye (light_measure.h's LookAt), which leaves
//           a constant for a renderer whose pixels sum to the light's energy wherever it falls;
//           llvmpipe's by what its points would sum to if each point of size s covered exactly
//           the disc of diameter s (PeerLightOf). Per light, over the frames its window is inside
//           the frame and no polygon hides part of it (at least --min_frames of them), the
//           ripple is (max - min) / mean of that ratio: the table gives each renderer's median
//           and worst light (which one), the worst of each row, and the centroid's wobble about
//           its projection. On the first frame, the lights measured alone are checked to add up
//           to the whole frame's light (the isolation is exact). Aperture's target: ripple at
//           most 1 % (moonshot 0.1 %).
//   edge    One light 1 km away passing behind the slanted edge of a wall 100 m away, frame by
//           frame (light_edge_run.h), at the first of --sizes and --aa.
//
// Exit status: 0 when Aperture met its targets (every light's ripple at most 1 %, the edge
// monotone with every step the covered area's change), 3 when it did not, 1 on an error, 2 on
// a bad flag.
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "absl/strings/str_split.h"
#include "io/exr_writer.h"
#include "light_edge_run.h"
#include "light_measure.h"
#include "light_point_peer.h"
#include "render/frame_renderer.h"
#include "scene/builtin_scenes.h"
#include "scene/scene_builder.h"
#include "scene/scene_file.h"
#include "support/runway_lights_scene.h"

namespace aperture {
namespace {

constexpr char kUsage[] = R"(usage: light_blink_bench [flags]

Light points on a slow approach, Aperture against Mesa llvmpipe drawing them as osgSim does
(GL_POINTS, GL_POINT_SMOOTH, additive blending, 1x and 4x MSAA): each steady light's energy per
frame over its analytic energy, its ripple (max - min) / mean over the approach (median, worst
light, worst per row of lights); then a light passing behind a wall's edge. Tables on stdout,
progress on stderr. Exit status 0 when Aperture met its targets (ripple <= 1 %, the edge
monotone and continuous), 3 when not, 1 on an error, 2 on a bad flag.

  --scene NAME|FILE    runway (this benchmark's own, the default), a built-in scene of the engine
                       (scene/builtin_scenes.h), or a scene file (.json, .gltf, .glb)
  --groups LIST        a built-in scene's lights of these groups only, comma separated (e.g. the
                       night scene's approach,runway-edge,runway-centre,touchdown-zone,
                       runway-threshold,runway-end); its polygons and attached lights dropped
  --aim X,Y,Z          the aiming point of the approach (default 0,0,-300: runway's)
  --heading DEG        the direction flown, a yaw: 0 along -z, 90 along -x (default 0)
  --start_m M          how far before the aiming point the approach starts (default 1800)
  --slope_deg DEG      the glide path's slope (default 3)
  --speed MPS          along the path (default 70)
  --fps F              frames a second (default 60)
  --frames N           frames of the approach (default 180: 3 s at 60 frames/s)
  --sizes WxH[,WxH]    frame sizes (default 1280x720)
  --aa LIST            Aperture's filters, of box2, box1, tent2 (default box2)
  --peer_min_sizes L   llvmpipe's minimum point sizes, pixels (default 1.5,0)
  --min_frames N       a light counts when measured in at least N frames (default 10)
  --threads N          Aperture measures lights on N threads (default 2)
  --edge_frames N      frames of the light behind an edge (default 120; 0: none)
  --edge_step PX       the edge's motion across the light per frame, pixels (default 0.025)
  --csv PATH           every measured light's every frame, one row each
  --preview PREFIX     Aperture's first frame of each size as PREFIX-WxH.png
  --help               this text
)";

struct Options {
  std::string scene = "runway";
  std::vector<std::string> groups;
  testing::GlidePath path;
  int frames = 180;
  double fps = 60;
  std::vector<std::pair<int, int>> sizes = {{1280, 720}};
  std::vector<AntiAliasing> aa = {AntiAliasing::kBox2};
  std::vector<double> peer_min_sizes = {1.5, 0};
  int min_frames = 10;
  int threads = 2;
  int edge_frames = 120;
  double edge_step = 0.025;
  std::string csv;
  std::string preview;
};

constexpr double kRippleTarget = 0.01;

// Of a scene, the lights of `groups` alone: no polygons (the runway's lights lie on flat ground,
// which hides none of them), so that each light's windows render fast.
absl::StatusOr<v1::Scene> LightsOfGroups(v1::Scene scene, const std::vector<std::string>& groups) {
  auto wanted = [&](const v1::LightPoint& l) {
    return l.object().empty() && std::find(groups.begin(), groups.end(), l.group()) != groups.end();
  };
  v1::Scene out;
  out.set_name(scene.name());
  *out.mutable_sky() = scene.sky();
  *out.mutable_fog() = scene.fog();
  *out.mutable_light_settings() = scene.light_settings();
  for (const v1::LightPoint& l : scene.lights())
    if (wanted(l)) *out.add_lights() = l;
  for (const v1::LightRow& r : scene.light_rows())
    if (wanted(r.light())) *out.add_light_rows() = r;
  if (out.lights_size() + out.light_rows_size() == 0)
    return absl::InvalidArgumentError("--groups: no light of the scene is in these groups");
  return out;
}

// The scene by --scene: this benchmark's runway, an engine built-in, or a file; --groups keeps
// a built-in scene's lights of those groups alone.
absl::StatusOr<Scene> LoadBenchScene(const std::string& name,
                                     const std::vector<std::string>& groups) {
  if (name == "runway" && groups.empty()) return BuildScene(testing::MakeRunwayLightsScene());
  auto builtin = FindBuiltinScene(name);
  if (builtin.ok() && groups.empty()) return BuildScene(builtin->scene);
  if (builtin.ok() || name == "runway") {
    auto lights = LightsOfGroups(
        name == "runway" ? testing::MakeRunwayLightsScene() : builtin->scene, groups);
    if (!lights.ok()) return lights.status();
    return BuildScene(*lights);
  }
  if (!groups.empty()) return absl::InvalidArgumentError("--groups: only for a built-in scene");
  if (NamesCountedBuiltinScene(name)) return builtin.status();
  if (!std::filesystem::exists(name))
    return absl::NotFoundError(absl::StrCat("--scene ", name,
                                            ": neither runway, a built-in scene nor a file (",
                                            builtin.status().message(), ")"));
  return LoadSceneFile(name);
}

// ---------------------------------------------------------------------------------------------
// The blink table.

// One light in one frame: its energy over the analytic energy, and its centroid less its
// projection (pixels).
struct Sample {
  double ratio = 0, dx = 0, dy = 0;
};

Sample SampleOf(const LightImage& image, double analytic, const LightView& lv) {
  return {image.sum / analytic, image.x - lv.x, image.y - lv.y};
}

struct Column {
  std::string name;
  bool aperture = false;
  std::vector<std::vector<Sample>> samples;  // per light, over the counted frames
};

struct LightName {
  std::string row;
  int index = 0;
};

std::vector<LightName> NamesOf(const Scene& scene) {
  std::vector<LightName> names;
  std::vector<int> count(scene.lights.groups.size() + 1, 0);
  for (const PointLight& light : scene.lights.lights) {
    const bool grouped = light.group >= 0;
    names.push_back({grouped ? scene.lights.groups[light.group].name : "(no group)",
                     count[grouped ? light.group + 1 : 0]++});
  }
  return names;
}

// A light over its frames: the ripple of its energy ((max - min) / mean of energy / analytic),
// and the wobble of its centroid (the farthest it strays from its mean offset to the projection).
struct Ripple {
  double ripple = 0, mean = 0, wobble = 0;
  int frames = 0;
};

Ripple RippleOf(const std::vector<Sample>& samples) {
  Ripple out;
  out.frames = static_cast<int>(samples.size());
  if (samples.empty()) return out;
  double sum = 0, dx = 0, dy = 0, low = INFINITY, high = -INFINITY;
  for (const Sample& s : samples) {
    sum += s.ratio;
    dx += s.dx;
    dy += s.dy;
    low = std::min(low, s.ratio);
    high = std::max(high, s.ratio);
  }
  const double n = static_cast<double>(samples.size());
  out.mean = sum / n;
  out.ripple = (high - low) / out.mean;
  for (const Sample& s : samples)
    out.wobble = std::max(out.wobble, std::hypot(s.dx - dx / n, s.dy - dy / n));
  return out;
}

// Prints the tables; true when every Aperture column met the ripple target.
bool PrintBlinkTable(const std::vector<Column>& columns, const std::vector<LightName>& names,
                     int min_frames) {
  bool met = true;
  std::printf(
      "\n| renderer | lights | frames each (median) | median ripple | worst ripple | worst light "
      "| energy / analytic (lights' means) | centroid wobble, median / worst (px) |\n"
      "|---|---:|---:|---:|---:|---|---|---|\n");
  std::string verdicts;
  for (const Column& c : columns) {
    std::vector<double> ripples, means, frames, wobbles;
    double worst = -1;
    size_t worst_light = 0;
    for (size_t i = 0; i < c.samples.size(); ++i) {
      const Ripple r = RippleOf(c.samples[i]);
      if (r.frames < min_frames) continue;
      ripples.push_back(r.ripple);
      means.push_back(r.mean);
      frames.push_back(r.frames);
      wobbles.push_back(r.wobble);
      if (r.ripple > worst) worst = r.ripple, worst_light = i;
    }
    if (ripples.empty()) {
      std::printf("| %s | 0 | | | | | | |\n", c.name.c_str());
      if (c.aperture) met = false;
      continue;
    }
    std::printf("| %s | %zu | %.0f | %.3g %% | %.3g %% | %s %d | %.6f .. %.6f | %.3f / %.3f |\n",
                c.name.c_str(), ripples.size(), Median(frames), 100 * Median(ripples), 100 * worst,
                names[worst_light].row.c_str(), names[worst_light].index,
                *std::min_element(means.begin(), means.end()),
                *std::max_element(means.begin(), means.end()), Median(wobbles),
                *std::max_element(wobbles.begin(), wobbles.end()));
    if (c.aperture) {
      const bool this_met = worst <= kRippleTarget;
      met = met && this_met;
      absl::StrAppend(
          &verdicts, c.name, ": worst ripple ", absl::StrFormat("%.3g", 100 * worst),
          " % against the target of 1 % (moonshot 0.1 %): ",
          this_met ? (worst <= kRippleTarget / 10 ? "met, moonshot too" : "met") : "MISSED", "\n");
    }
  }
  std::printf("\n%s", verdicts.c_str());
  std::printf(
      "(llvmpipe draws multisampled points as squares of whole sizes, their energy 4/pi of the "
      "discs': a square's count of samples never changes as it moves, so its energy cannot "
      "ripple. The 4x MSAA figures hold for llvmpipe's squares, not for a GPU drawing the discs "
      "GL's multisample rasterization of points describes.)\n");
  // The worst ripple of each row of lights.
  std::vector<std::string> rows;
  for (const LightName& n : names)
    if (std::find(rows.begin(), rows.end(), n.row) == rows.end()) rows.push_back(n.row);
  std::printf("\nworst ripple by row of lights:\n\n| row |");
  for (const Column& c : columns) std::printf(" %s |", c.name.c_str());
  std::printf("\n|---|");
  for (size_t k = 0; k < columns.size(); ++k) std::printf("---:|");
  std::printf("\n");
  for (const std::string& row : rows) {
    std::printf("| %s |", row.c_str());
    for (const Column& c : columns) {
      double worst = 0;
      int counted = 0;
      for (size_t i = 0; i < c.samples.size(); ++i) {
        if (names[i].row != row) continue;
        const Ripple r = RippleOf(c.samples[i]);
        if (r.frames < min_frames) continue;
        worst = std::max(worst, r.ripple);
        ++counted;
      }
      if (counted == 0)
        std::printf(" - |");
      else
        std::printf(" %.3g %% |", 100 * worst);
    }
    std::printf("\n");
  }
  std::fflush(stdout);
  return met;
}

std::string PeerName(double min_size, bool msaa) {
  return absl::StrCat("llvmpipe ", msaa ? "4x MSAA" : "1x", ", min ", min_size, " px");
}

// Aperture's frame `camera` sees: the whole frame's light (with the lights less without) against
// the sum of every drawn light measured alone, relative. Lights on objects are not placed by
// LookAt: a scene with any is not checked (-1).
absl::StatusOr<double> AdditivityError(const Scene& scene, const Scene& dark,
                                       const RenderSettings& settings, const Camera& camera,
                                       ApertureLightProbe& probe) {
  for (const PointLight& light : scene.lights.lights)
    if (light.object >= 0) return -1;
  auto with = RenderFrame(scene, camera, settings);
  if (!with.ok()) return with.status();
  auto without = RenderFrame(dark, camera, settings);
  if (!without.ok()) return without.status();
  double whole = 0;
  for (size_t p = 0; p < with->image.texels().size(); ++p)
    whole += Luminance(with->image.texels()[p]) - Luminance(without->image.texels()[p]);
  const FrameView view(camera, settings.width, settings.height);
  double alone = 0;
  for (const PointLight& light : scene.lights.lights) {
    const LightView lv = LookAt(scene, light, view);
    if (!lv.drawn) continue;
    auto sample = probe.Measure(light, camera, lv.window, false);
    if (!sample.ok()) return sample.status();
    alone += sample->image.sum;
  }
  return std::abs(alone - whole) / whole;
}

// The approach at one size; `met` is cleared when Aperture misses its ripple target.
absl::Status RunBlink(LightPointPeer& peer, const Scene& scene, int width, int height,
                      const Options& o, std::ofstream* csv, bool& met) {
  Scene dark = scene;
  dark.lights.lights.clear();
  const std::vector<PointLight>& lights = scene.lights.lights;
  const std::vector<LightName> names = NamesOf(scene);
  if (!peer.Resize(width, height))
    return absl::InternalError(absl::StrCat("llvmpipe's buffers of ", width, "x", height));
  RenderSettings settings;
  settings.width = width;
  settings.height = height;
  settings.threads = 0;  // the caller's arena: lights are measured in parallel
  if (!o.preview.empty()) {
    RenderSettings whole = settings;
    whole.aa = o.aa.front();
    auto frame = RenderFrame(scene, o.path.At(0), whole);
    if (!frame.ok()) return frame.status();
    const std::string file = absl::StrCat(o.preview, "-", width, "x", height, ".png");
    if (auto s = WritePngPreview(frame->image, file); !s.ok()) return s;
  }

  std::vector<Column> columns;
  for (AntiAliasing aa : o.aa)
    columns.push_back({absl::StrCat("Aperture ", AntiAliasingName(aa)), true, {}});
  for (double m : o.peer_min_sizes)
    for (bool msaa : {false, true}) columns.push_back({PeerName(m, msaa), false, {}});
  for (Column& c : columns) c.samples.assign(lights.size(), {});
  std::vector<int> occluded_frames(lights.size(), 0);
  size_t unsteady = 0;
  for (const PointLight& light : lights) unsteady += !SteadyWorldLight(light);

  // Each filter's probe per worker thread.
  std::vector<std::unique_ptr<tbb::enumerable_thread_specific<ApertureLightProbe>>> probes;
  for (AntiAliasing aa : o.aa) {
    RenderSettings s = settings;
    s.aa = aa;
    probes.push_back(std::make_unique<tbb::enumerable_thread_specific<ApertureLightProbe>>(
        [&scene, &dark, s] { return ApertureLightProbe(scene, dark, s); }));
  }
  tbb::task_arena arena(o.threads);
  double additivity = -1;
  for (int k = 0; k < o.frames; ++k) {
    const Camera camera = o.path.At(k / o.fps);
    const FrameView view(camera, width, height);
    std::vector<LightView> lv(lights.size());
    std::vector<size_t> counted;
    for (size_t i = 0; i < lights.size(); ++i) {
      if (!SteadyWorldLight(lights[i])) continue;
      lv[i] = LookAt(scene, lights[i], view);
      if (!lv[i].drawn) continue;
      // Room in the window for the largest point the peer draws.
      double room = 0;
      for (double m : o.peer_min_sizes)
        for (const PeerPoint& p : PeerLightOf(lights[i], lv[i], camera.position, m).points)
          room = std::max(room, p.point.size / 2.0 + 1);
      lv[i] = LookAt(scene, lights[i], view, room);
      if (lv[i].inside) counted.push_back(i);
    }
    if (k == 0) {
      RenderSettings whole = settings;
      whole.aa = o.aa.front();
      absl::StatusOr<double> error = -1.0;
      arena.execute(
          [&] { error = AdditivityError(scene, dark, whole, camera, probes.front()->local()); });
      if (!error.ok()) return error.status();
      additivity = *error;
    }
    // Aperture, each light in parallel.
    std::vector<std::vector<ApertureLightSample>> ap(
        o.aa.size(), std::vector<ApertureLightSample>(counted.size()));
    absl::Status failure;
    std::mutex failure_mutex;
    for (size_t a = 0; a < o.aa.size(); ++a) {
      arena.execute([&] {
        tbb::parallel_for(size_t{0}, counted.size(), [&](size_t j) {
          const size_t i = counted[j];
          auto sample = probes[a]->local().Measure(lights[i], camera, lv[i].window, true);
          if (sample.ok()) {
            ap[a][j] = *sample;
          } else {
            std::lock_guard<std::mutex> lock(failure_mutex);
            failure = sample.status();
          }
        });
      });
      if (!failure.ok()) return failure;
    }
    // A light some polygon hides in part is counted by no renderer that frame: its energy is
    // meant to change.
    std::vector<bool> keep(counted.size(), true);
    for (size_t j = 0; j < counted.size(); ++j)
      for (size_t a = 0; a < o.aa.size(); ++a)
        if (ap[a][j].occluded) keep[j] = false;
    for (size_t j = 0; j < counted.size(); ++j) {
      const size_t i = counted[j];
      if (!keep[j]) {
        ++occluded_frames[i];
        continue;
      }
      for (size_t a = 0; a < o.aa.size(); ++a)
        columns[a].samples[i].push_back(
            SampleOf(ap[a][j].image, lv[i].energy * Luminance(lights[i].color), lv[i]));
    }
    // llvmpipe, light by light into its window.
    peer.SetCamera(camera);
    size_t column = o.aa.size();
    for (double m : o.peer_min_sizes) {
      for (bool msaa : {false, true}) {
        for (size_t j = 0; j < counted.size(); ++j) {
          if (!keep[j]) continue;
          const size_t i = counted[j];
          const PeerLight pl = PeerLightOf(lights[i], lv[i], camera.position, m);
          peer.Begin(msaa, lv[i].window);
          peer.DrawPoints(pl.points);
          peer.End(lv[i].window);
          columns[column].samples[i].push_back(SampleOf(
              ImageOf(peer.WindowLuminance(lv[i].window), lv[i].window), pl.nominal, lv[i]));
        }
        ++column;
      }
    }
    if (csv != nullptr) {
      for (size_t j = 0; j < counted.size(); ++j) {
        if (!keep[j]) continue;
        const size_t i = counted[j];
        *csv << width << 'x' << height << ',' << k << ',' << names[i].row << ',' << names[i].index
             << ',' << lv[i].distance << ',' << lv[i].x << ',' << lv[i].y << ',' << lv[i].energy
             << ',' << lv[i].footprint_px;
        for (const Column& c : columns)
          *csv << ',' << c.samples[i].back().ratio << ',' << c.samples[i].back().dx << ','
               << c.samples[i].back().dy;
        *csv << '\n';
      }
    }
    if (k % 30 == 0)
      std::fprintf(stderr, "  %dx%d frame %d/%d: %zu lights measured\n", width, height, k, o.frames,
                   counted.size());
  }
  std::printf(
      "\nblink, %dx%d, scene %s: %d frames (%.2f s at %g frames/s), %zu lights (%zu flashing or "
      "on objects, not measured), the camera from %.0f to %.0f m before the aiming point; "
      "ripple = (max - min) / mean of energy / analytic over the frames a light is inside the "
      "frame and unoccluded (at least %d)\n",
      width, height, o.scene.c_str(), o.frames, o.frames / o.fps, o.fps, lights.size(), unsteady,
      o.path.DistanceAt(0), o.path.DistanceAt((o.frames - 1) / o.fps), o.min_frames);
  if (additivity >= 0)
    std::printf(
        "additivity, first frame, Aperture %s: the lights measured alone sum to the whole "
        "frame's light within %.1e of it\n",
        AntiAliasingName(o.aa.front()), additivity);
  int occluded_lights = 0;
  for (int f : occluded_frames) occluded_lights += f > 0;
  if (occluded_lights > 0)
    std::printf("(%d lights were partly hidden by polygons in some frames, which are left out)\n",
                occluded_lights);
  if (!PrintBlinkTable(columns, names, o.min_frames)) met = false;
  return absl::OkStatus();
}

// ---------------------------------------------------------------------------------------------

bool ParseDoubles(const std::string& s, std::vector<double>& out) {
  out.clear();
  for (absl::string_view part : absl::StrSplit(s, ',', absl::SkipEmpty())) {
    const std::string text(part);
    char* end = nullptr;
    const double v = std::strtod(text.c_str(), &end);
    if (end == text.c_str() || *end != '\0' || !std::isfinite(v)) return false;
    out.push_back(v);
  }
  return !out.empty();
}

bool ParseDouble(const std::string& s, double& out) {
  std::vector<double> v;
  if (!ParseDoubles(s, v) || v.size() != 1) return false;
  out = v.front();
  return true;
}

bool ParseInt(const std::string& s, int least, int& out) {
  double v = 0;
  if (!ParseDouble(s, v) || v != std::floor(v) || v < least || v > 1e7) return false;
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
    std::vector<double> list;
    if (flag == "--scene") {
      o.scene = value;
    } else if (flag == "--groups") {
      o.groups = absl::StrSplit(value, ',', absl::SkipEmpty());
      if (o.groups.empty()) return bad("wants group names, comma separated");
    } else if (flag == "--aim") {
      if (!ParseDoubles(value, list) || list.size() != 3) return bad("wants X,Y,Z");
      o.path.aim = {list[0], list[1], list[2]};
    } else if (flag == "--heading") {
      if (!ParseDouble(value, o.path.heading_deg)) return bad("wants degrees");
    } else if (flag == "--start_m") {
      if (!ParseDouble(value, o.path.start_distance_m) || o.path.start_distance_m <= 0)
        return bad("wants metres > 0");
    } else if (flag == "--slope_deg") {
      if (!ParseDouble(value, o.path.slope_deg) || o.path.slope_deg <= 0 || o.path.slope_deg >= 45)
        return bad("wants degrees in (0, 45)");
    } else if (flag == "--speed") {
      if (!ParseDouble(value, o.path.speed_mps) || o.path.speed_mps < 0)
        return bad("wants metres a second >= 0");
    } else if (flag == "--fps") {
      if (!ParseDouble(value, o.fps) || o.fps <= 0) return bad("wants frames a second > 0");
    } else if (flag == "--frames") {
      if (!ParseInt(value, 2, o.frames)) return bad("wants a whole number >= 2");
    } else if (flag == "--sizes") {
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
    } else if (flag == "--aa") {
      o.aa.clear();
      for (absl::string_view part : absl::StrSplit(value, ',', absl::SkipEmpty())) {
        if (part == "box1") {
          o.aa.push_back(AntiAliasing::kBox1);
        } else if (part == "box2") {
          o.aa.push_back(AntiAliasing::kBox2);
        } else if (part == "tent2") {
          o.aa.push_back(AntiAliasing::kTent2);
        } else {
          return bad("wants box2, box1 or tent2, comma separated");
        }
      }
      if (o.aa.empty()) return bad("wants box2, box1 or tent2");
    } else if (flag == "--peer_min_sizes") {
      if (!ParseDoubles(value, o.peer_min_sizes)) return bad("wants pixels, comma separated");
      for (double m : o.peer_min_sizes)
        if (m < 0 || m > 30) return bad("wants sizes in 0..30 pixels");
    } else if (flag == "--min_frames") {
      if (!ParseInt(value, 2, o.min_frames)) return bad("wants a whole number >= 2");
    } else if (flag == "--threads") {
      if (!ParseInt(value, 1, o.threads)) return bad("wants a whole number >= 1");
    } else if (flag == "--edge_frames") {
      if (!ParseInt(value, 0, o.edge_frames)) return bad("wants a whole number >= 0");
    } else if (flag == "--edge_step") {
      if (!ParseDouble(value, o.edge_step) || o.edge_step <= 0 || o.edge_step > 1)
        return bad("wants pixels in (0, 1]");
    } else if (flag == "--csv") {
      o.csv = value;
    } else if (flag == "--preview") {
      o.preview = value;
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
    std::fprintf(stderr, "light_blink_bench: %s\n", std::string(s.message()).c_str());
    return 2;
  }
  if (help) {
    std::printf("%s", kUsage);
    return 0;
  }
  auto fail = [](const absl::Status& s) {
    std::fprintf(stderr, "light_blink_bench: %s\n", std::string(s.message()).c_str());
    return 1;
  };
  auto scene = LoadBenchScene(o.scene, o.groups);
  if (!scene.ok()) return fail(scene.status());
  if (std::none_of(scene->lights.lights.begin(), scene->lights.lights.end(), SteadyWorldLight))
    return fail(absl::InvalidArgumentError(
        absl::StrCat("--scene ", o.scene, ": no steady light point in world space to measure (of ",
                     scene->lights.lights.size(),
                     " lights; flashing lights and lights on "
                     "objects are left out)")));
  LightPointPeer peer;
  if (!peer.Init()) return 1;
  std::printf("light points: Aperture against %s drawing them as osgSim does\n",
              peer.Renderer().c_str());
  std::ofstream csv;
  if (!o.csv.empty()) {
    csv.open(o.csv);
    if (!csv) return fail(absl::NotFoundError(absl::StrCat("--csv ", o.csv, ": cannot write")));
    csv << "size,frame,row,index,distance_m,x,y,energy,footprint_px";
    // Per renderer: energy / analytic, and the centroid less the projection (pixels).
    std::vector<std::string> renderers;
    for (AntiAliasing aa : o.aa)
      renderers.push_back(absl::StrCat("aperture_", AntiAliasingName(aa)));
    for (double m : o.peer_min_sizes)
      for (const char* mode : {"1x", "4x"})
        renderers.push_back(absl::StrCat("llvmpipe_", mode, "_min", m));
    for (const std::string& r : renderers) csv << ',' << r << ',' << r << "_dx," << r << "_dy";
    csv << '\n';
  }
  bool met = true;
  for (const auto& [w, h] : o.sizes)
    if (auto s = RunBlink(peer, *scene, w, h, o, o.csv.empty() ? nullptr : &csv, met); !s.ok())
      return fail(s);
  if (o.edge_frames > 1) {
    EdgeRunOptions edge;
    edge.width = o.sizes.front().first;
    edge.height = o.sizes.front().second;
    edge.aa = o.aa.front();
    edge.frames = o.edge_frames;
    edge.step_px = o.edge_step;
    edge.peer_min_size = o.peer_min_sizes.front();
    bool passed = false;
    if (auto s = RunEdge(peer, edge, &passed); !s.ok()) return fail(s);
    met = met && passed;
  }
  return met ? 0 : 3;
}

}  // namespace
}  // namespace aperture

int main(int argc, char** argv) { return aperture::Run(argc, argv); }
