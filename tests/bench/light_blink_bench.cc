// Do light points blink? Aperture against Mesa llvmpipe drawing the same lights as
// OpenSceneGraph-based image generators do (osgSim: smooth GL points, light_point_peer.h), on the
// same frames, each light's energy measured from the images.
//
//   blink   A slow approach: the 3 degree glide path at --speed m/s, --fps frames a second for
//           --frames frames, towards a runway lit by rows of lights (support/runway_lights_scene.h:
//           edge, centre line, threshold, end, approach row and crossbar; 266 lights), at each of
//           --sizes. For every light in every frame its energy is measured from an image holding
//           that light alone: Aperture renders the light's window of the frame (`region`) with the
//           light and without it and sums the difference's Rec. 709 luminance; llvmpipe draws the
//           light's points alone into the same window (light_point_peer.h says of which buffers).
//           The energy divided by the analytic one, exposure x I / d^2 / (one pixel's solid angle)
//           x the colour's luminance, is constant for a renderer whose pixels sum to the light's
//           energy wherever it falls. llvmpipe's points are held to the same energy: its ratio is
//           the measured sum over what the points would sum to if each point of size s covered
//           exactly the disc of diameter s (PeerLightOf says why that equals scaling their
//           colour to Aperture's energy). Per light, over the frames where its window is inside
//           the frame and Aperture finds it unoccluded (at least --min_frames of them), the
//           ripple is (max - min) / mean of that ratio; the table gives the median and the worst
//           light.
//           llvmpipe runs with the minimum point size of Aperture's footprint (1.5 px) and with
//           osgSim's default minimum (0: sub-pixel points faded by alpha), each 1x and 4x MSAA.
//   time    Every --time_every frames, the light-only scene (no ground) as a whole frame,
//           interleaved: Aperture (--threads), llvmpipe 1x and 4x MSAA (LP_NUM_THREADS), the
//           points in their colours (unscaled: the time does not depend on it).
//   edge    One light 1 km away passing behind the slanted edge of a wall 100 m away as the
//           camera slides sideways (--edge_step pixels a frame, --edge_frames frames, first of
//           --sizes): its energy per frame against the analytic visible share of its footprint
//           (the octagon Aperture draws, clipped by the wall's projected quad). Aperture must dim
//           monotonically with no step larger than the share's own change; llvmpipe's points are
//           depth tested against the wall and pop.
//
// Usage: light_blink_bench [--frames N] [--fps F] [--speed MPS] [--sizes WxH,WxH]
//            [--aa box2,box1,tent2] [--peer_min_sizes 1.5,0] [--min_frames N] [--time_every N]
//            [--threads N] [--edge_frames N] [--edge_step PX] [--csv PATH] [--preview PREFIX]
// (scripts/bench-lights.sh installs OSMesa, builds and runs it with LP_NUM_THREADS=2.)
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_split.h"
#include "io/exr_writer.h"
#include "light_point_peer.h"
#include "raster/projection.h"
#include "render/frame_renderer.h"
#include "scene/scene_builder.h"
#include "scene/triangulate.h"
#include "support/runway_lights_scene.h"

namespace aperture {
namespace {

double Now() {
  return std::chrono::duration<double, std::milli>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

double Median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

double Luminance(const Rgba& c) { return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b; }

struct Options {
  int frames = 180;
  double fps = 60, speed = 70;
  std::vector<std::pair<int, int>> sizes = {{1280, 720}, {1920, 1080}};
  std::vector<AntiAliasing> aa = {AntiAliasing::kBox2, AntiAliasing::kBox1, AntiAliasing::kTent2};
  std::vector<double> peer_min_sizes = {1.5, 0};
  int min_frames = 10;
  int time_every = 6;  // 0: no timing
  int threads = 2;
  int edge_frames = 120;
  double edge_step = 0.025;
  std::string csv;
  std::string preview;  // a path prefix: Aperture's first frame of each size as PREFIX-WxH.png
};

// ---------------------------------------------------------------------------------------------
// Where a light falls and what it should sum to, from the camera alone.

struct View {
  Camera camera;
  int width, height;
  FrustumTangents t;
  double sx, sy;  // tangent-plane extent of one pixel
  Mat3 to_camera;

  View(const Camera& c, int w, int h)
      : camera(c),
        width(w),
        height(h),
        t(ResolveFrustum(c, w, h)),
        sx((t.right - t.left) / w),
        sy((t.top - t.bottom) / h),
        to_camera(c.Orientation().Transposed()) {}
};

struct LightView {
  bool ahead = false;
  double x = 0, y = 0;      // the projection, pixels (row 0 at the top)
  double distance = 0;      // metres
  double energy = 0;        // S, pixel values: exposure x I / d^2 / (one pixel's solid angle)
  double lamp_px = 0;       // the lamp's projected radius, pixels
  double footprint_px = 0;  // Aperture's footprint radius (docs/SCENE.md, "Light points")
  PixelRect window;         // the pixels its image may reach, with room to spare
  bool inside = false;      // the window lies inside the frame
};

LightView Look(const PointLight& light, const LightSettings& settings, const View& v,
               double peer_half_size) {
  LightView out;
  const Vec3 d = light.position - v.camera.position;
  const Vec3 p = v.to_camera * d;
  if (!(-p.z > v.camera.near)) return out;
  out.ahead = true;
  out.distance = Length(d);
  const double tx = p.x / -p.z, ty = p.y / -p.z;
  out.x = (tx - v.t.left) / v.sx;
  out.y = (v.t.top - ty) / v.sy;
  // The solid angle of one pixel at (tx, ty) on the tangent plane at distance 1.
  const double pixel_sr = v.sx * v.sy / std::pow(1 + tx * tx + ty * ty, 1.5);
  out.energy = settings.exposure * light.intensity_cd / (out.distance * out.distance) / pixel_sr;
  out.lamp_px = light.radius_m / out.distance / v.sy;
  const double min_radius = settings.min_size_px / 2;
  double r = std::max(min_radius, out.lamp_px);
  const double lum = out.energy * Luminance(light.color);
  if (lum > 2) r = std::max(r, min_radius * std::pow(lum / 2, 0.25));
  out.footprint_px = std::min(r, 64.0);
  const int half =
      static_cast<int>(std::ceil(std::max(1.06 * out.footprint_px, peer_half_size))) + 3;
  const int cx = static_cast<int>(std::floor(out.x)), cy = static_cast<int>(std::floor(out.y));
  out.window = {cx - half, cy - half, cx + half + 1, cy + half + 1};
  out.inside = out.window.x0 >= 0 && out.window.y0 >= 0 && out.window.x1 <= v.width &&
               out.window.y1 <= v.height;
  return out;
}

// osgSim's points for a light: projected lamp radius x sqrt(intensity), osgSim's intensity 1
// taken as 1,000 cd, in the light's colour (at most 1: the buffers clamp, as an image generator's
// do). `nominal` is the luminance they would sum to if each point of size s covered exactly the
// disc of diameter s. Scaling their colour by S / nominal would give them the light's energy S
// (Aperture's); blending is linear and a measured light is drawn alone, so measured / nominal is
// the same ratio to the analytic energy without that scaling, which the clamped buffers could not
// hold.
struct PeerLight {
  std::vector<PeerPoint> points;
  double nominal = 0;
};

PeerLight PeerLightOf(const PointLight& light, const LightView& lv, const Vec3& eye,
                      double min_size) {
  const std::vector<SizedPoint> sizes =
      OsgSimPointSizes(lv.lamp_px * std::sqrt(light.intensity_cd / 1000), min_size);
  const double peak = std::max({light.color.r, light.color.g, light.color.b, 1.0f});
  const Rgba color{light.color.r / static_cast<float>(peak),
                   light.color.g / static_cast<float>(peak),
                   light.color.b / static_cast<float>(peak), 1};
  PeerLight out;
  out.nominal = NominalArea(sizes) * Luminance(color);
  for (const SizedPoint& s : sizes)
    out.points.push_back({light.position - eye, color.r, color.g, color.b, s});
  return out;
}

// ---------------------------------------------------------------------------------------------
// Aperture: one light's energy from the images of its window with it and without it.

// A light's image in its window: its luminance summed, its centroid, and whether any of it
// reached the window's border (the window was too small to hold it).
struct LightImage {
  double sum = 0, x = 0, y = 0;
  bool at_border = false;
};

// `luminance`: the window's pixels row by row from the top.
LightImage ImageOf(const std::vector<double>& luminance, const PixelRect& window) {
  LightImage out;
  double mx = 0, my = 0, border = 0;
  for (int y = 0; y < window.height(); ++y)
    for (int x = 0; x < window.width(); ++x) {
      const double v = luminance[static_cast<size_t>(y) * window.width() + x];
      out.sum += v;
      mx += v * (window.x0 + x + 0.5);
      my += v * (window.y0 + y + 0.5);
      if (x == 0 || y == 0 || x == window.width() - 1 || y == window.height() - 1)
        border += std::abs(v);
    }
  out.x = mx / out.sum;
  out.y = my / out.sum;
  out.at_border = border > 1e-6 * std::abs(out.sum);
  return out;
}

// One light in one frame: its energy over the analytic energy, and its centroid less its
// projection (pixels).
struct Sample {
  double ratio = 0, dx = 0, dy = 0;
};

Sample SampleOf(const LightImage& image, double nominal, const LightView& lv) {
  return {image.sum / nominal, image.x - lv.x, image.y - lv.y};
}

struct Measured {
  Sample sample;
  bool occluded = false;
};

// The rows of a band of render/light_pass.cc (kBandRows there; if they part, the windows are cut
// into bands differently from a whole frame, and the whole-frame check of RunTiming still holds).
constexpr int kLightBandRows = 32;

class ApertureProbe {
 public:
  ApertureProbe(const Scene& scene, AntiAliasing aa, int width, int height)
      : lit_(scene), dark_(scene) {
    dark_.lights.lights.clear();
    settings_.width = width;
    settings_.height = height;
    settings_.aa = aa;
    settings_.threads = 0;  // the caller's arena: lights are measured in parallel
  }

  // Light `light` alone, over `lv.window` widened upwards to a multiple of the light pass's bands
  // of rows: a band starts every kLightBandRows rows from the region's top, so the region's bands
  // are the whole frame's and a footprint is cut into bands as a whole frame cuts it.
  Measured Measure(const PointLight& light, const Camera& camera, const LightView& lv) {
    lit_.lights.lights.assign(1, light);
    RenderSettings settings = settings_;
    settings.region = lv.window;
    settings.region.y0 = lv.window.y0 / kLightBandRows * kLightBandRows;
    auto with = RenderFrame(lit_, camera, settings);
    auto without = RenderFrame(dark_, camera, settings);
    if (!with.ok() || !without.ok()) {
      std::fprintf(stderr, "light_blink_bench: %s\n",
                   std::string((with.ok() ? without.status() : with.status()).message()).c_str());
      std::exit(1);
    }
    const Image& a = with->image;
    const Image& b = without->image;
    std::vector<double> luminance(static_cast<size_t>(a.width()) * a.height());
    for (int y = 0; y < a.height(); ++y)
      for (int x = 0; x < a.width(); ++x)
        luminance[static_cast<size_t>(y) * a.width() + x] =
            Luminance(a.at(x, y)) - Luminance(b.at(x, y));
    const LightImage image = ImageOf(luminance, settings.region);
    if (image.at_border) {
      std::fprintf(stderr, "light_blink_bench: a light's image reaches its window's border\n");
      std::exit(1);
    }
    return {SampleOf(image, lv.energy * Luminance(light.color), lv),
            with->stats.lights_occluded > 0};
  }

 private:
  Scene lit_, dark_;
  RenderSettings settings_;
};

// ---------------------------------------------------------------------------------------------
// The blink table.

struct Column {
  std::string name;
  std::vector<std::vector<Sample>> samples;  // per light, over the counted frames
};

struct LightName {
  std::string row;
  int index = 0;
};

std::vector<LightName> NamesOf(const Scene& scene) {
  std::vector<LightName> names;
  std::vector<int> count(scene.lights.groups.size(), 0);
  for (const PointLight& light : scene.lights.lights)
    names.push_back({scene.lights.groups[light.group].name, count[light.group]++});
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

void PrintBlinkTable(const std::vector<Column>& columns, const std::vector<LightName>& names,
                     int min_frames) {
  std::printf(
      "\n| renderer | lights | frames each (median) | median ripple | worst ripple | worst light "
      "| energy / analytic (lights' means) | centroid wobble, median / worst (px) |\n"
      "|---|---:|---:|---:|---:|---|---|---|\n");
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
      continue;
    }
    std::printf("| %s | %zu | %.0f | %.3g %% | %.3g %% | %s %d | %.6f .. %.6f | %.3f / %.3f |\n",
                c.name.c_str(), ripples.size(), Median(frames), 100 * Median(ripples), 100 * worst,
                names[worst_light].row.c_str(), names[worst_light].index,
                *std::min_element(means.begin(), means.end()),
                *std::max_element(means.begin(), means.end()), Median(wobbles),
                *std::max_element(wobbles.begin(), wobbles.end()));
  }
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
}

std::string PeerName(double min_size, bool msaa) {
  return absl::StrCat("llvmpipe ", msaa ? "4x MSAA" : "1x", ", min ", min_size, " px");
}

void RunBlink(LightPointPeer& peer, int width, int height, const Options& o, std::ofstream* csv) {
  testing::RunwayLightsOptions ro;
  auto scene = BuildScene(testing::MakeRunwayLightsScene(ro));
  if (!scene.ok()) {
    std::fprintf(stderr, "light_blink_bench: %s\n", std::string(scene.status().message()).c_str());
    std::exit(1);
  }
  const std::vector<PointLight>& lights = scene->lights.lights;
  const LightSettings& ls = scene->lights.settings;
  const std::vector<LightName> names = NamesOf(*scene);
  const testing::GlidePath path{1800, o.speed, 3};
  if (!peer.Resize(width, height)) std::exit(1);
  if (!o.preview.empty()) {
    RenderSettings settings;
    settings.width = width;
    settings.height = height;
    settings.aa = o.aa.front();
    auto frame = RenderFrame(*scene, path.At(0), settings);
    const std::string file = absl::StrCat(o.preview, "-", width, "x", height, ".png");
    if (!frame.ok() || !WritePngPreview(frame->image, file).ok())
      std::fprintf(stderr, "light_blink_bench: could not write %s\n", file.c_str());
  }

  std::vector<Column> columns;
  for (AntiAliasing aa : o.aa)
    columns.push_back({absl::StrCat("Aperture ", AntiAliasingName(aa)), {}});
  for (double m : o.peer_min_sizes)
    for (bool msaa : {false, true}) columns.push_back({PeerName(m, msaa), {}});
  for (Column& c : columns) c.samples.assign(lights.size(), {});
  std::vector<int> occluded_frames(lights.size(), 0);

  // Each renderer's probe per worker thread: a copy of the scene whose lights it swaps.
  std::vector<std::unique_ptr<tbb::enumerable_thread_specific<ApertureProbe>>> probes;
  for (AntiAliasing aa : o.aa)
    probes.push_back(std::make_unique<tbb::enumerable_thread_specific<ApertureProbe>>(
        [&, aa] { return ApertureProbe(*scene, aa, width, height); }));
  const double start = Now();
  double aperture_ms = 0, peer_ms = 0;
  for (int k = 0; k < o.frames; ++k) {
    const Camera camera = path.At(k / o.fps);
    const View view(camera, width, height);
    std::vector<LightView> lv(lights.size());
    std::vector<size_t> counted;
    for (size_t i = 0; i < lights.size(); ++i) {
      lv[i] = Look(lights[i], ls, view, 0);
      if (!lv[i].ahead) continue;
      // Room in the window for the largest point the peer draws.
      double peer_half = 0;
      for (double m : o.peer_min_sizes)
        for (const PeerPoint& p : PeerLightOf(lights[i], lv[i], camera.position, m).points)
          peer_half = std::max(peer_half, p.point.size / 2.0 + 1);
      lv[i] = Look(lights[i], ls, view, peer_half);
      if (lv[i].ahead && lv[i].inside) counted.push_back(i);
    }
    // Aperture, each light in parallel.
    const double aperture_start = Now();
    std::vector<std::vector<Measured>> ap(o.aa.size(), std::vector<Measured>(counted.size()));
    for (size_t a = 0; a < o.aa.size(); ++a) {
      tbb::parallel_for(size_t{0}, counted.size(), [&](size_t j) {
        const size_t i = counted[j];
        ap[a][j] = probes[a]->local().Measure(lights[i], camera, lv[i]);
      });
    }
    // A light some polygon hides in part is counted by no renderer that frame.
    std::vector<bool> keep(counted.size(), true);
    for (size_t j = 0; j < counted.size(); ++j)
      for (size_t a = 0; a < o.aa.size(); ++a)
        if (ap[a][j].occluded) keep[j] = false;
    for (size_t j = 0; j < counted.size(); ++j) {
      if (!keep[j]) {
        ++occluded_frames[counted[j]];
        continue;
      }
      for (size_t a = 0; a < o.aa.size(); ++a)
        columns[a].samples[counted[j]].push_back(ap[a][j].sample);
    }
    aperture_ms += Now() - aperture_start;
    // llvmpipe, light by light.
    const double peer_start = Now();
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
    peer_ms += Now() - peer_start;
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
      std::fprintf(stderr,
                   "  %dx%d frame %d/%d: %zu lights measured, %.1f s (Aperture %.1f s, "
                   "llvmpipe %.1f s)\n",
                   width, height, k, o.frames, counted.size(), (Now() - start) / 1000,
                   aperture_ms / 1000, peer_ms / 1000);
  }
  std::printf(
      "\nblink, %dx%d: %d frames (%.2f s at %g frames/s), %zu lights, the camera from %.0f "
      "to %.0f m before the aiming point; ripple = (max - min) / mean of energy / analytic "
      "over the frames a light is inside the frame and unoccluded (at least %d)\n",
      width, height, o.frames, o.frames / o.fps, o.fps, lights.size(), path.start_distance_m,
      path.start_distance_m - o.speed * std::cos(3 * M_PI / 180) * (o.frames - 1) / o.fps,
      o.min_frames);
  int occluded_lights = 0;
  for (int f : occluded_frames) occluded_lights += f > 0;
  if (occluded_lights > 0)
    std::printf("(%d lights were partly occluded in some frames, which are left out)\n",
                occluded_lights);
  PrintBlinkTable(columns, names, o.min_frames);
}

// ---------------------------------------------------------------------------------------------
// Time per frame of the light-only scene, interleaved.

void RunTiming(LightPointPeer& peer, int width, int height, const Options& o) {
  testing::RunwayLightsOptions ro;
  ro.surfaces = false;
  auto scene = BuildScene(testing::MakeRunwayLightsScene(ro));
  if (!scene.ok()) std::exit(1);
  const std::vector<PointLight>& lights = scene->lights.lights;
  const testing::GlidePath path{1800, o.speed, 3};
  if (!peer.Resize(width, height)) std::exit(1);
  RenderSettings settings;
  settings.width = width;
  settings.height = height;
  settings.aa = o.aa.front();
  settings.threads = o.threads;
  const double min_size = o.peer_min_sizes.front();
  std::vector<double> ap, gl1, gl4, light_pass;
  // The whole frame's energy against the sum of the lights' analytic energies: the lights'
  // footprints cut into bands of rows lose and double nothing.
  double whole_low = INFINITY, whole_high = -INFINITY;
  auto aperture_frame = [&](const Camera& camera) {
    const double t0 = Now();
    auto frame = RenderFrame(*scene, camera, settings);
    const double ms = Now() - t0;
    if (!frame.ok()) std::exit(1);
    light_pass.push_back(frame->stats.lights_ms);
    const View view(camera, width, height);
    double analytic = 0;
    bool all_inside = true;
    for (const PointLight& light : lights) {
      const LightView lv = Look(light, scene->lights.settings, view, 0);
      all_inside = all_inside && lv.ahead && lv.inside;
      analytic += lv.energy * Luminance(light.color);
    }
    if (all_inside) {
      double sum = 0;  // the sky is black: every pixel value is light
      for (const Rgba& p : frame->image.texels()) sum += Luminance(p);
      whole_low = std::min(whole_low, sum / analytic);
      whole_high = std::max(whole_high, sum / analytic);
    }
    return ms;
  };
  auto peer_frame = [&](const Camera& camera, bool msaa) {
    const View view(camera, width, height);
    const double t0 = Now();
    std::vector<PeerPoint> points;
    for (const PointLight& light : lights) {
      const LightView lv = Look(light, scene->lights.settings, view, 0);
      if (!lv.ahead) continue;
      for (const PeerPoint& p : PeerLightOf(light, lv, camera.position, min_size).points)
        points.push_back(p);
    }
    peer.SetCamera(camera);
    peer.Begin(msaa, {}, /*eight_bit=*/true);
    peer.DrawPoints(points);
    peer.End();
    return Now() - t0;
  };
  // Not counted: llvmpipe compiles its shaders, the allocators warm up.
  aperture_frame(path.At(0));
  peer_frame(path.At(0), false);
  peer_frame(path.At(0), true);
  light_pass.clear();
  for (int k = 0; k < o.frames; k += o.time_every) {
    const Camera camera = path.At(k / o.fps);
    ap.push_back(aperture_frame(camera));
    gl1.push_back(peer_frame(camera, false));
    gl4.push_back(peer_frame(camera, true));
  }
  std::printf(
      "\ntime per frame, %dx%d, the %zu lights alone, median of %zu frames of the approach, "
      "interleaved: Aperture %s %.2f ms (its light pass %.2f ms; --threads %d) | llvmpipe 1x "
      "%.2f ms | llvmpipe 4x MSAA %.2f ms (8-bit buffers, min %g px, LP_NUM_THREADS=%s)\n",
      width, height, lights.size(), ap.size(), AntiAliasingName(settings.aa), Median(ap),
      Median(light_pass), o.threads, Median(gl1), Median(gl4), min_size,
      std::getenv("LP_NUM_THREADS") ? std::getenv("LP_NUM_THREADS") : "(unset)");
  if (whole_low <= whole_high)
    std::printf("Aperture's whole frames: energy / the lights' analytic energies %.7f .. %.7f\n",
                whole_low, whole_high);
  std::fflush(stdout);
}

// ---------------------------------------------------------------------------------------------
// A light passing behind an edge.

// Area of a convex polygon clipped by another convex polygon (Sutherland-Hodgman).
double ClippedArea(std::vector<Vec2> subject, const std::vector<Vec2>& clip) {
  const double orientation = SignedArea(clip) > 0 ? 1 : -1;
  for (size_t e = 0; e < clip.size() && !subject.empty(); ++e) {
    const Vec2 a = clip[e], b = clip[(e + 1) % clip.size()];
    auto side = [&](const Vec2& p) {
      return orientation * ((b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x));
    };
    std::vector<Vec2> out;
    for (size_t i = 0; i < subject.size(); ++i) {
      const Vec2 p = subject[i], q = subject[(i + 1) % subject.size()];
      const double sp = side(p), sq = side(q);
      if (sp >= 0) out.push_back(p);
      if ((sp >= 0) != (sq >= 0)) {
        const double t = sp / (sp - sq);
        out.push_back({p.x + t * (q.x - p.x), p.y + t * (q.y - p.y)});
      }
    }
    subject = std::move(out);
  }
  return subject.size() < 3 ? 0 : std::abs(SignedArea(subject));
}

// The footprint as Aperture draws it: the regular octagon of the disc's area.
std::vector<Vec2> Octagon(double x, double y, double radius) {
  const double circumradius = radius * std::sqrt(M_PI / (2 * std::sqrt(2.0)));
  std::vector<Vec2> v;
  for (int k = 0; k < 8; ++k) {
    const double a = (k + 0.5) * M_PI / 4;
    v.push_back({x + circumradius * std::cos(a), y + circumradius * std::sin(a)});
  }
  return v;
}

void RunEdge(LightPointPeer& peer, int width, int height, const Options& o) {
  constexpr double kLightDepth = 1000, kWallDepth = 100, kEye = 2, kSlopeDeg = 20;
  constexpr double kWantedEnergy = 1.5;  // below the bloom: the footprint keeps its 1.5 px
  const double f = height / 2.0 / std::tan(M_PI / 6);  // pixels per unit tangent
  const double dx = o.edge_step / (f * (1 / kWallDepth - 1 / kLightDepth));
  const Vec3 light_at{0.37, kEye + 0.13, -kLightDepth};
  // The wall's left edge meets the light's row 1.5 px (at the light's screen scale) right of it.
  const double row_y = kEye + 0.13 * kWallDepth / kLightDepth;
  const double travel = o.edge_step * o.edge_frames;
  const double xe = kWallDepth * (light_at.x / kLightDepth + 0.5 * travel / f) -
                    (row_y - kEye) * std::tan(kSlopeDeg * M_PI / 180);
  const double tan_slope = std::tan(kSlopeDeg * M_PI / 180);
  // The wall: from its slanted left edge 15 m to the right, 10 m high around the eye.
  Vec3 wall[4] = {{xe - 5 * tan_slope, kEye - 5, -kWallDepth},
                  {xe + 15, kEye - 5, -kWallDepth},
                  {xe + 15, kEye + 5, -kWallDepth},
                  {xe + 5 * tan_slope, kEye + 5, -kWallDepth}};
  v1::Scene proto;
  proto.set_name("light behind an edge");
  v1::Material& grey = *proto.add_materials();
  grey.set_id("wall");
  grey.set_unlit(true);
  grey.mutable_base_color()->set_r(0.2f);
  grey.mutable_base_color()->set_g(0.2f);
  grey.mutable_base_color()->set_b(0.2f);
  v1::Mesh& mesh = *proto.add_meshes();
  mesh.set_id("wall");
  mesh.set_material_id("wall");
  v1::Polygon& quad = *mesh.add_polygons();
  for (const Vec3& c : wall) {
    v1::Vec3& v = *quad.add_vertices();
    v.set_x(c.x);
    v.set_y(c.y);
    v.set_z(c.z);
  }
  // Its intensity gives S = kWantedEnergy at this size.
  Camera camera;
  camera.position = {0, kEye, 0};
  const View v0(camera, width, height);
  v1::LightPoint& lp = *proto.add_lights();
  lp.mutable_position()->set_x(light_at.x);
  lp.mutable_position()->set_y(light_at.y);
  lp.mutable_position()->set_z(light_at.z);
  lp.set_intensity_cd(1000);
  {
    PointLight probe;
    probe.position = light_at;
    probe.intensity_cd = 1000;
    LightSettings defaults;
    lp.set_intensity_cd(1000 * kWantedEnergy / Look(probe, defaults, v0, 0).energy);
  }
  auto scene = BuildScene(proto);
  if (!scene.ok()) {
    std::fprintf(stderr, "light_blink_bench: %s\n", std::string(scene.status().message()).c_str());
    std::exit(1);
  }
  const PointLight light = scene->lights.lights.front();
  const double min_size = o.peer_min_sizes.front();
  if (!peer.Resize(width, height)) std::exit(1);
  ApertureProbe probe(*scene, o.aa.front(), width, height);
  RenderSettings settings;
  settings.width = width;
  settings.height = height;
  settings.aa = o.aa.front();
  settings.threads = 1;

  std::printf(
      "\nedge, %dx%d: a light 1 km away (S = %.2f, footprint 1.5 px) behind the edge of a wall "
      "100 m away, slanted %g degrees, the edge moving %.3g px a frame across it; energy / "
      "analytic per frame\n\n| frame | visible share (analytic) | Aperture %s | llvmpipe 1x | "
      "llvmpipe 4x MSAA |\n|---:|---:|---:|---:|---:|\n",
      width, height, kWantedEnergy, kSlopeDeg, o.edge_step, AntiAliasingName(settings.aa));
  std::vector<double> share, aperture, gl1, gl4;
  for (int k = 0; k < o.edge_frames; ++k) {
    camera.position = {k * dx, kEye, 0};
    const View view(camera, width, height);
    const LightView lv = Look(light, scene->lights.settings, view, 2.5);
    if (!lv.inside || lv.footprint_px != 0.75) {
      std::fprintf(stderr, "light_blink_bench: the edge light left the frame or bloomed\n");
      std::exit(1);
    }
    // The analytic share: the octagon less the wall's projected quad.
    const FrameGeometry geo = ProjectScene(*scene, camera, width, height, 2);
    std::vector<Vec2> wall_screen(geo.polygons.front().vertices.begin(),
                                  geo.polygons.front().vertices.end());
    const std::vector<Vec2> octagon = Octagon(lv.x, lv.y, lv.footprint_px);
    const double visible = 1 - ClippedArea(octagon, wall_screen) / std::abs(SignedArea(octagon));
    share.push_back(visible);
    // Aperture: the window with the light less without it.
    aperture.push_back(probe.Measure(light, camera, lv).sample.ratio);
    // llvmpipe: the wall, then the points depth tested against it; less the wall alone.
    peer.SetCamera(camera);
    for (bool msaa : {false, true}) {
      peer.Begin(msaa, lv.window);
      peer.DrawQuad(wall, 0.2f);
      peer.End(lv.window);
      const std::vector<double> dark = peer.WindowLuminance(lv.window);
      const PeerLight pl = PeerLightOf(light, lv, camera.position, min_size);
      peer.Begin(msaa, lv.window);
      peer.DrawQuad(wall, 0.2f);
      peer.DrawPoints(pl.points);
      peer.End(lv.window);
      std::vector<double> lit = peer.WindowLuminance(lv.window);
      for (size_t p = 0; p < lit.size(); ++p) lit[p] -= dark[p];
      const LightImage image = ImageOf(lit, lv.window);
      (msaa ? gl4 : gl1).push_back(image.sum / pl.nominal);
    }
    std::printf("| %d | %.5f | %.5f | %.5f | %.5f |\n", k, visible, aperture.back(), gl1.back(),
                gl4.back());
  }
  // Aperture: monotone, each step within the share's own change.
  double worst_error = 0, worst_excess = 0, largest_share_step = 0;
  int rises = 0;
  for (size_t k = 0; k < share.size(); ++k) {
    worst_error = std::max(worst_error, std::abs(aperture[k] - share[k]));
    if (k == 0) continue;
    const double step = aperture[k] - aperture[k - 1], want = share[k] - share[k - 1];
    largest_share_step = std::max(largest_share_step, std::abs(want));
    rises += step > 1e-6;
    worst_excess = std::max(worst_excess, std::abs(step) - std::abs(want));
  }
  auto largest_step = [](const std::vector<double>& e) {
    double s = 0;
    for (size_t k = 1; k < e.size(); ++k) s = std::max(s, std::abs(e[k] - e[k - 1]));
    return s;
  };
  std::printf(
      "\nAperture: %s (%d rising steps), largest step %.5f against the share's largest change "
      "%.5f, worst step beyond the share's change %+.2e, worst |energy - share| %.2e\n"
      "llvmpipe 1x: largest step %.5f (%.1fx the share's); 4x MSAA: largest step %.5f (%.1fx)\n",
      rises == 0 ? "monotone" : "NOT monotone", rises, largest_step(aperture), largest_share_step,
      worst_excess, worst_error, largest_step(gl1), largest_step(gl1) / largest_share_step,
      largest_step(gl4), largest_step(gl4) / largest_share_step);
  std::fflush(stdout);
}

// ---------------------------------------------------------------------------------------------

template <typename T>
std::vector<T> ParseList(const std::string& s) {
  std::vector<T> out;
  for (absl::string_view part : absl::StrSplit(s, ',', absl::SkipEmpty()))
    out.push_back(static_cast<T>(std::strtod(std::string(part).c_str(), nullptr)));
  return out;
}

bool ParseOptions(int argc, char** argv, Options& o) {
  for (int i = 1; i < argc; i += 2) {
    const std::string flag = argv[i];
    if (i + 1 >= argc) return false;
    const std::string value = argv[i + 1];
    if (flag == "--frames") {
      o.frames = std::max(2, std::atoi(value.c_str()));
    } else if (flag == "--fps") {
      o.fps = std::strtod(value.c_str(), nullptr);
    } else if (flag == "--speed") {
      o.speed = std::strtod(value.c_str(), nullptr);
    } else if (flag == "--sizes") {
      o.sizes.clear();
      for (absl::string_view part : absl::StrSplit(value, ',', absl::SkipEmpty())) {
        int w = 0, h = 0;
        if (std::sscanf(std::string(part).c_str(), "%dx%d", &w, &h) != 2 || w < 64 || h < 64)
          return false;
        o.sizes.push_back({w, h});
      }
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
          return false;
        }
      }
    } else if (flag == "--peer_min_sizes") {
      o.peer_min_sizes = ParseList<double>(value);
    } else if (flag == "--min_frames") {
      o.min_frames = std::max(2, std::atoi(value.c_str()));
    } else if (flag == "--time_every") {
      o.time_every = std::max(0, std::atoi(value.c_str()));
    } else if (flag == "--threads") {
      o.threads = std::max(1, std::atoi(value.c_str()));
    } else if (flag == "--edge_frames") {
      o.edge_frames = std::max(0, std::atoi(value.c_str()));
    } else if (flag == "--edge_step") {
      o.edge_step = std::strtod(value.c_str(), nullptr);
    } else if (flag == "--csv") {
      o.csv = value;
    } else if (flag == "--preview") {
      o.preview = value;
    } else {
      return false;
    }
  }
  return !o.sizes.empty() && !o.aa.empty() && !o.peer_min_sizes.empty() && o.fps > 0 &&
         o.edge_step > 0;
}

}  // namespace
}  // namespace aperture

int main(int argc, char** argv) {
  aperture::Options o;
  if (!aperture::ParseOptions(argc, argv, o)) {
    std::fprintf(stderr,
                 "usage: light_blink_bench [--frames N] [--fps F] [--speed MPS] [--sizes WxH,WxH] "
                 "[--aa box2,box1,tent2] [--peer_min_sizes 1.5,0] [--min_frames N] "
                 "[--time_every N] [--threads N] [--edge_frames N] [--edge_step PX] "
                 "[--csv PATH] [--preview PREFIX]\n");
    return 2;
  }
  aperture::LightPointPeer peer;
  if (!peer.Init()) return 1;
  std::printf("light points: Aperture against %s drawing them as osgSim does\n",
              peer.Renderer().c_str());
  std::ofstream csv;
  if (!o.csv.empty()) {
    csv.open(o.csv);
    csv << "size,frame,row,index,distance_m,x,y,energy,footprint_px";
    // Per renderer: energy / analytic, and the centroid less the projection (pixels).
    std::vector<std::string> renderers;
    for (aperture::AntiAliasing aa : o.aa)
      renderers.push_back(std::string("aperture_") + aperture::AntiAliasingName(aa));
    for (double m : o.peer_min_sizes)
      for (const char* mode : {"1x", "4x"})
        renderers.push_back(absl::StrCat("llvmpipe_", mode, "_min", m));
    for (const std::string& r : renderers) csv << ',' << r << ',' << r << "_dx," << r << "_dy";
    csv << '\n';
  }
  for (const auto& [w, h] : o.sizes) {
    aperture::RunBlink(peer, w, h, o, o.csv.empty() ? nullptr : &csv);
    if (o.time_every > 0) aperture::RunTiming(peer, w, h, o);
  }
  if (o.edge_frames > 1) aperture::RunEdge(peer, o.sizes.front().first, o.sizes.front().second, o);
  return 0;
}
