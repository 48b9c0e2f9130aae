// Edge anti-aliasing benchmark: frame time of the 10,000-triangle field at 1920x1080
// and the quality of its edges against a dense box reference (65,536 samples per aperture), as
// PSNR over randomly chosen edge pixels. Usage: edge_quality_bench [REPEAT] [EDGE_PIXELS]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>

#include "raster/projection.h"
#include "render/frame_renderer.h"
#include "scene/benchmark_scenes.h"
#include "scene/scene_builder.h"
#include "support/reference_render.h"

namespace aperture {
namespace {

int Main(int repeat, int edge_pixels) {
  auto scene = BuildScene(MakeTriangleFieldScene(10000));
  if (!scene.ok()) return 1;
  Camera camera;
  camera.position = {0, 0, 0};
  std::printf("scene: 10,000 triangles, 1920x1080, camera at the origin looking along -z\n");
  for (AntiAliasing aa : {AntiAliasing::kBox2, AntiAliasing::kBox1}) {
    RenderSettings settings;
    settings.aa = aa;
    settings.threads = 2;
    double best_ms = 1e30;
    absl::StatusOr<RenderedFrame> frame;
    for (int i = 0; i < repeat; ++i) {
      frame = RenderFrame(*scene, camera, settings);
      if (!frame.ok()) return 1;
      best_ms = std::min(best_ms, frame->stats.setup_ms + frame->stats.raster_ms);
    }
    // Edge pixels: apertures that more than one polygon (or a polygon and the sky) share.
    const double margin = ShapeOf(aa).margin;
    const FrameGeometry geo = ProjectScene(*scene, camera, 1920, 1080, margin + 1);
    std::mt19937 rng(5);
    std::uniform_int_distribution<int> px(0, 1919), py(0, 1079);
    double sum_sq = 0, worst = 0;
    int measured = 0;
    while (measured < edge_pixels) {
      const int x = px(rng), y = py(rng);
      FrameGeometry local = geo;
      local.polygons.clear();
      bool partial = false;
      for (const ScreenPolygon& p : geo.polygons) {
        const double x0 = x - margin, x1 = x + 1 + margin, y0 = y - margin, y1 = y + 1 + margin;
        if (p.max_x <= x0 || p.min_x >= x1 || p.max_y <= y0 || p.min_y >= y1) continue;
        local.polygons.push_back(p);
        partial = partial || !(p.Contains(x0, y0) && p.Contains(x1, y0) && p.Contains(x1, y1) &&
                               p.Contains(x0, y1));
      }
      if (!partial) continue;
      // Each polygon's colour is the renderer's own shading at the pixel centre (flat, lit).
      const RenderedFrame& f = *frame;
      auto colour = [&](int k) {
        const ScreenPolygon& p = local.polygons[k];
        return scene->materials[p.material].base_color * p.light;
      };
      const Rgba want = testing::DenseReferencePixel(local, colour, scene->sky, aa, x, y, 256);
      const Rgba got = f.image.at(x, y);
      for (double d : {got.r - want.r, got.g - want.g, got.b - want.b}) {
        sum_sq += d * d;
        worst = std::max(worst, std::abs(d));
      }
      ++measured;
    }
    const double mse = sum_sq / (3.0 * measured);
    std::printf(
        "%-5s frame %.1f ms (2 threads, fastest of %d); %d edge pixels vs dense reference: "
        "PSNR %.1f dB, max error %.2e\n",
        AntiAliasingName(aa), best_ms, repeat, measured, 10 * std::log10(1.0 / mse), worst);
  }
  return 0;
}

}  // namespace
}  // namespace aperture

int main(int argc, char** argv) {
  const int repeat = argc > 1 ? std::max(1, std::atoi(argv[1])) : 3;
  const int pixels = argc > 2 ? std::max(1, std::atoi(argv[2])) : 500;
  return aperture::Main(repeat, pixels);
}
