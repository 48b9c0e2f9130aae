#include "render/frame_renderer.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <chrono>
#include <cmath>

#include "absl/strings/str_cat.h"
#include "raster/projection.h"
#include "render/leaf_renderer.h"

namespace aperture {
namespace {

double MillisecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
      .count();
}

}  // namespace

absl::Status ValidateRenderSettings(const RenderSettings& s) {
  if (s.width <= 0 || s.height <= 0 || s.width > kMaxImageSide || s.height > kMaxImageSide)
    return absl::InvalidArgumentError(absl::StrCat("image size ", s.width, "x", s.height,
                                                   " is outside 1..", kMaxImageSide, " per side"));
  if (!std::isfinite(s.shading.texture_aperture) || s.shading.texture_aperture <= 0 ||
      s.shading.texture_aperture > 16)
    return absl::InvalidArgumentError("texture aperture must be in (0, 16] pixels");
  if (s.threads < 0) return absl::InvalidArgumentError("threads must be >= 0");
  if (s.warnock.leaf_size < 1 || s.warnock.root_size < 1)
    return absl::InvalidArgumentError("Warnock leaf and root sizes must be >= 1");
  return absl::OkStatus();
}

absl::StatusOr<RenderedFrame> RenderFrame(const Scene& scene, const Camera& camera,
                                          const RenderSettings& settings) {
  if (auto s = ValidateRenderSettings(settings); !s.ok()) return s;
  if (auto s = ValidateCamera(camera); !s.ok()) return s;

  RenderedFrame frame;
  frame.image = Image::Uninitialized(settings.width, settings.height);
  const AaFilterShape shape = ShapeOf(settings.aa);
  tbb::task_arena arena(settings.threads > 0 ? settings.threads : tbb::task_arena::automatic);
  arena.execute([&] {
    auto start = std::chrono::steady_clock::now();
    const FrameGeometry geometry =
        ProjectScene(scene, camera, settings.width, settings.height, shape.margin + 1.0);
    const PolygonShader shader(scene, geometry, settings.shading);
    frame.stats.setup_ms = MillisecondsSince(start);
    frame.stats.visible_polygons = geometry.polygons.size();

    start = std::chrono::steady_clock::now();
    const PixelRect whole{0, 0, settings.width, settings.height};
    const std::vector<LeafWindow> leaves =
        SubdivideWarnock(geometry, shape, whole, settings.warnock);
    tbb::enumerable_thread_specific<LeafRenderer> renderers(
        [&] { return LeafRenderer(geometry, shader, settings.aa, scene.sky); });
    tbb::parallel_for(size_t{0}, leaves.size(),
                      [&](size_t i) { renderers.local().Render(leaves[i], frame.image); });
    frame.stats.raster_ms = MillisecondsSince(start);
    for (const LeafWindow& leaf : leaves) {
      switch (leaf.kind) {
        case LeafWindow::Kind::kEmpty:
          ++frame.stats.empty_leaves;
          break;
        case LeafWindow::Kind::kCovered:
          ++frame.stats.covered_leaves;
          break;
        case LeafWindow::Kind::kMixed:
          ++frame.stats.mixed_leaves;
          break;
      }
    }
  });
  return frame;
}

}  // namespace aperture
