// The raytrace quality benchmark: seed 003's raytrace mode against every raster texture filter on
// DESIGN.md's grazing plane, all driven with the pixel-square aperture a = 1 and compared with
// the a = 1 reference (the bilinear texture averaged over the pixel square by at least 64 x 64
// stratified samples per pixel, more where the footprint spans more texels).
//
// The raytrace images come from the real mode (TracedScene: Embree corner rays on a 40 km ground
// polygon, fragments, summed-area tables); the raster filters from their samplers on the plane's
// analytic footprints, as `aperture-bench filter` measures them.
//
// A second table covers the curved primitives the raster mode cannot draw (testing/curved_scenes:
// a checkerboard sphere, a lit capped cylinder), at each of --curved-sizes: raytrace against the
// bilinear texture point-sampled at the pixel centre and supersampled 2 x 2, 4 x 4 and 8 x 8,
// all against the 64 x 64-sample reference (testing/supersample_reference).
//
// Usage: raytrace_quality_bench [--textures checker,asphalt_torcs_1024] [--angles 5,20,60]
//          [--delta 0.1] [--exact-steps 0,64] [--threads 2] [--data ../shared/data/raster]
//          [--out out/raytrace-bench]
//          [--ref-min 64] [--ref-max 128] [--curved-sizes 48,192] [--max-depth 3]
//          (--textures "" or --curved-sizes "": skip that table)
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_split.h"
#include "io/exr_writer.h"
#include "render/trace_renderer.h"
#include "scene/scene.h"
#include "scene/scene_builder.h"
#include "testing/curved_scenes.h"
#include "testing/grazing_plane.h"
#include "testing/supersample_reference.h"
#include "texture/image_file.h"
#include "texture/reference_sampler.h"

namespace aperture {
namespace {

// The a = 1 reference with at least `min_side` x `min_side` strata per pixel.
Image Reference(const GrazingPlaneView& view, const Image& texture, int min_side, int max_side) {
  Image out(view.width, view.height);
  const double n = texture.width();
  tbb::parallel_for(0, view.height, [&](int j) {
    TextureFootprint f, far;
    for (int i = 0; i < view.width; ++i) {
      if (!GroundFootprint(view, i, j, &f)) {
        out.at(i, j) = {0, 0, 0, 1};
        continue;
      }
      far = f;
      if (j > 0) GroundFootprint(view, i, j - 1, &far);
      auto strata = [&](double d) {
        return std::clamp(static_cast<int>(std::ceil(d * n * 2)), min_side, max_side);
      };
      const int kx = strata(std::max(std::abs(f.dudx), std::abs(far.dudx)));
      const int ky = strata(std::max(std::hypot(f.dudy, f.dvdy), std::hypot(far.dudy, far.dvdy)));
      const uint64_t key = static_cast<uint64_t>(j) * view.width + i;
      double r = 0, g = 0, b = 0;
      for (int sy = 0; sy < ky; ++sy)
        for (int sx = 0; sx < kx; ++sx) {
          const double px = i + (sx + StratumJitter(key, sx, sy, 0)) / kx;
          const double py = j + (sy + StratumJitter(key, sx, sy, 1)) / ky;
          double u, v;
          if (!GroundPoint(view, px, py, &u, &v)) continue;  // sky contributes 0
          const Rgba c = BilinearPeriodic(texture, u - std::floor(u), v - std::floor(v));
          r += c.r, g += c.g, b += c.b;
        }
      const double inv = 1.0 / (static_cast<double>(kx) * ky);
      out.at(i, j) = {static_cast<float>(r * inv), static_cast<float>(g * inv),
                      static_cast<float>(b * inv), 1.0f};
    }
  });
  return out;
}

std::map<std::string, std::string> ParseFlags(int argc, char** argv) {
  std::map<std::string, std::string> flags;
  for (int i = 1; i + 1 < argc; i += 2) flags[argv[i]] = argv[i + 1];
  return flags;
}

double Seconds(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The curved scenes' table (see the file comment); 0 or 2 (error).
int RunCurved(const std::vector<int>& sizes, double delta, const std::vector<int>& exact_steps,
              int max_depth, const std::string& out_dir) {
  std::printf(
      "\n| scene | size | centre | 2x2 | 4x4 | 8x8 | exact steps | exact pixels | raytrace | "
      "raytrace - best supersample | mean S_frag/S_quad - 1 (fragment pixels) | fragments / "
      "fragment pixel | raytrace ms |\n"
      "|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (const CurvedSceneKind kind : {CurvedSceneKind::kSphere, CurvedSceneKind::kCylinder}) {
    const CurvedTestScene test = MakeCurvedTestScene(kind);
    auto scene = BuildScene(test.scene);
    auto traced = scene.ok() ? TracedScene::Build(*scene) : scene.status();
    if (!traced.ok()) {
      std::fprintf(stderr, "%s\n", std::string(traced.status().message()).c_str());
      return 2;
    }
    const RayScene& rays = (*traced)->rays();
    for (const int size : sizes) {
      const std::string name = test.scene.name();
      const std::string cache = absl::StrCat(out_dir, "/cache/ref_", name, "_", size, "_n64.exr");
      Image ref;
      if (std::filesystem::exists(cache)) {
        ref = *LoadImageFile(cache);
      } else {
        const auto start = std::chrono::steady_clock::now();
        ref = RenderSupersampled(*scene, rays, test.camera, size, size, {64, true});
        ExrOptions exr;
        exr.pixel_type = ExrPixelType::kFloat;
        if (!WriteExrFile(ref, exr, cache).ok()) return 2;
        std::fprintf(stderr, "%s %d: reference in %.1f s\n", name.c_str(), size, Seconds(start));
      }
      double psnr[4];
      const int strata[4] = {1, 2, 4, 8};
      double best = -INFINITY;
      for (int k = 0; k < 4; ++k) {
        const Image img =
            RenderSupersampled(*scene, rays, test.camera, size, size, {strata[k], strata[k] > 1});
        psnr[k] = Psnr(img, ref, 0);
        best = std::max(best, psnr[k]);
        (void)WriteExrFile(img, {},
                           absl::StrCat(out_dir, "/", name, "_", size, "_ss", strata[k], ".exr"));
      }
      RenderSettings settings;
      settings.width = settings.height = size;
      for (const int steps : exact_steps) {
        TraceOptions options;
        options.fragments.delta = delta;
        options.fragments.exact_steps = steps;
        options.max_depth = max_depth;
        TraceStats stats;
        auto frame = (*traced)->Render(test.camera, settings, options, &stats);
        if (!frame.ok()) {
          std::fprintf(stderr, "%s\n", std::string(frame.status().message()).c_str());
          return 2;
        }
        const double rt = Psnr(frame->image, ref, 0);
        (void)WriteExrFile(
            frame->image, {},
            absl::StrCat(out_dir, "/", name, "_", size, "_raytrace_exact", steps, ".exr"));
        std::printf(
            "| %s | %d | %.2f | %.2f | %.2f | %.2f | %d | %.1f %% | %.2f | %+.2f | %.4f | %.1f | "
            "%.0f |\n",
            name.c_str(), size, psnr[0], psnr[1], psnr[2], psnr[3], steps,
            100 * stats.fragments.ExactShare(), rt, rt - best,
            stats.fragments.FragmentMeanRelativeError(),
            stats.fragments.quads > 0 ? stats.fragments.fragments / stats.fragments.quads : 0.0,
            stats.corner_ms + stats.shade_ms);
        std::fflush(stdout);
      }
      (void)WriteExrFile(ref, {}, absl::StrCat(out_dir, "/", name, "_", size, "_reference.exr"));
    }
  }
  return 0;
}

int Run(int argc, char** argv) {
  auto flags = ParseFlags(argc, argv);
  auto get = [&](const char* name, const char* fallback) {
    return flags.count(name) ? flags[name] : std::string(fallback);
  };
  const std::string out_dir = get("--out", "out/raytrace-bench");
  const double delta = std::atof(get("--delta", "0.1").c_str());
  const int threads = std::atoi(get("--threads", "2").c_str());
  const int ref_min = std::atoi(get("--ref-min", "64").c_str());
  const int ref_max = std::atoi(get("--ref-max", "128").c_str());
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, std::max(1, threads));
  std::filesystem::create_directories(out_dir + "/cache");
  std::vector<int> exact_step_list;
  for (absl::string_view a :
       absl::StrSplit(get("--exact-steps", std::to_string(FragmentOptions{}.exact_steps).c_str()),
                      ',', absl::SkipEmpty()))
    exact_step_list.push_back(std::atoi(std::string(a).c_str()));
  std::vector<double> angles;
  for (absl::string_view a : absl::StrSplit(get("--angles", "5,20,60"), ','))
    angles.push_back(std::atof(std::string(a).c_str()));

  std::printf(
      "| texture | theta | nearest | bilinear | trilinear | aniso | oiio | exact steps | exact "
      "pixels | raytrace | raytrace - best raster | mean S_frag/S_quad - 1 (fragment pixels) | "
      "fragments / fragment pixel | raytrace ms |\n"
      "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  std::fflush(stdout);
  for (absl::string_view part :
       absl::StrSplit(get("--textures", "checker,asphalt_torcs_1024"), ',', absl::SkipEmpty())) {
    const std::string name(part);
    Image image;
    if (name == "checker") {
      image = MakeCheckerboard(1024, 8, {1, 1, 1, 1}, {0, 0, 0, 1});
    } else {
      auto loaded = LoadImageFile(get("--data", "../shared/data/raster") + "/" + name + ".png");
      if (!loaded.ok()) {
        std::fprintf(stderr, "%s\n", std::string(loaded.status().message()).c_str());
        return 2;
      }
      image = ResizeToPowerOfTwo(*loaded);
    }
    auto texture = MakeSceneTexture(name, image);
    const Scene scene = GrazingPlaneScene(texture);
    auto traced = TracedScene::Build(scene);
    if (!traced.ok()) {
      std::fprintf(stderr, "%s\n", std::string(traced.status().message()).c_str());
      return 2;
    }
    for (double theta : angles) {
      GrazingPlaneView view;
      view.pitch_deg = theta;
      view.aperture = 1;
      const int first = FirstMeasuredRow(view);
      const std::string cache = absl::StrCat(out_dir, "/cache/ref_", name, "_p", theta, "_a1_min",
                                             ref_min, "_max", ref_max, ".exr");
      Image ref;
      if (std::filesystem::exists(cache)) {
        ref = *LoadImageFile(cache);
      } else {
        const auto start = std::chrono::steady_clock::now();
        ref = Reference(view, image, ref_min, ref_max);
        ExrOptions exr;
        exr.pixel_type = ExrPixelType::kFloat;
        if (!WriteExrFile(ref, exr, cache).ok()) return 2;
        std::fprintf(stderr, "%s theta %g: reference in %.1f s\n", name.c_str(), theta,
                     Seconds(start));
      }
      const std::string stem = absl::StrCat(out_dir, "/", name, "_p", theta, "_a1");
      double psnr[5];
      const FilterMode modes[5] = {FilterMode::kNearest, FilterMode::kBilinear,
                                   FilterMode::kTrilinear, FilterMode::kAniso, FilterMode::kOiio};
      double best_raster = -INFINITY;
      for (int m = 0; m < 5; ++m) {
        auto sampler = texture->Sampler(modes[m]);
        if (!sampler.ok()) {
          std::fprintf(stderr, "%s\n", sampler.status().ToString().c_str());
          return 2;
        }
        const Image img = RenderGroundImage(view, **sampler);
        psnr[m] = Psnr(img, ref, first);
        best_raster = std::max(best_raster, psnr[m]);
        (void)WriteExrFile(img, {}, absl::StrCat(stem, "_", FilterModeName(modes[m]), ".exr"));
      }
      Camera camera;
      camera.position = {0, 1, 0};
      camera.pitch_deg = -theta;
      camera.vertical_fov_deg = view.fov_deg;
      camera.near = 0.01;
      RenderSettings settings;
      settings.width = view.width;
      settings.height = view.height;
      // One raytrace per --exact-steps value (0: seed 003's fragments for every pixel), each a row.
      for (int exact_steps : exact_step_list) {
        TraceOptions options;
        options.fragments.delta = delta;
        options.fragments.exact_steps = exact_steps;
        TraceStats stats;
        auto frame = (*traced)->Render(camera, settings, options, &stats);
        if (!frame.ok()) {
          std::fprintf(stderr, "%s\n", std::string(frame.status().message()).c_str());
          return 2;
        }
        const double rt = Psnr(frame->image, ref, first);
        (void)WriteExrFile(frame->image, {},
                           absl::StrCat(stem, "_raytrace_exact", exact_steps, ".exr"));
        std::printf(
            "| %s | %g | %.2f | %.2f | %.2f | %.2f | %.2f | %d | %.1f %% | %.2f | %+.2f | %.4f | "
            "%.1f | %.0f |\n",
            name.c_str(), theta, psnr[0], psnr[1], psnr[2], psnr[3], psnr[4], exact_steps,
            100 * stats.fragments.ExactShare(), rt, rt - best_raster,
            stats.fragments.FragmentMeanRelativeError(),
            stats.fragments.quads > 0 ? stats.fragments.fragments / stats.fragments.quads : 0.0,
            stats.corner_ms + stats.shade_ms);
        std::fflush(stdout);
      }
      (void)WriteExrFile(ref, {}, absl::StrCat(stem, "_reference.exr"));
    }
  }
  std::vector<int> curved_sizes;
  for (absl::string_view a :
       absl::StrSplit(get("--curved-sizes", "48,192"), ',', absl::SkipEmpty()))
    curved_sizes.push_back(std::atoi(std::string(a).c_str()));
  if (!curved_sizes.empty())
    return RunCurved(curved_sizes, delta, exact_step_list,
                     std::atoi(get("--max-depth", "3").c_str()), out_dir);
  return 0;
}

}  // namespace
}  // namespace aperture

int main(int argc, char** argv) { return aperture::Run(argc, argv); }
