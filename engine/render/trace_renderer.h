// Seed 003's render mode (--mode raytrace): rays through the (W + 1) x (H + 1) pixel corners, each
// shared by its four pixels, traced with Embree on oneTBB tiles. A pixel whose four corners hit
// one polygon takes the texture's integral over the corners' quad abcd in the texture plane
// (fragments and summed-area tables); a pixel whose corners disagree (an edge, a corner in the
// sky) is split into four with more corner rays, down to a bounded depth, and its sub-pixels are
// weighted by area. Shading matches the raster path (render/polygon_shader): base colour times
// texture, Lambert sun plus ambient on the side facing the camera, distance fog.
#pragma once

#include <memory>
#include <vector>

#include "absl/status/statusor.h"
#include "render/renderer.h"
#include "scene/camera.h"
#include "scene/scene.h"
#include "store/shared_store.h"
#include "texture/summed_area_table.h"
#include "trace/projection_integral.h"
#include "trace/ray_scene.h"
#include "trace/texture_integral.h"

namespace aperture {

struct TraceOptions {
  FragmentOptions fragments;  // delta: the allowed relative area error (seed 003, eq. 9)
  int max_depth = 3;          // pixel subdivisions where corners disagree: 4^3 sub-pixels at most
};

// delta > 0 and max_depth in [0, 8]; names the offending option.
absl::Status ValidateTraceOptions(const TraceOptions& options);

struct TraceStats {
  double corner_ms = 0;  // the (W + 1) x (H + 1) corner rays
  double shade_ms = 0;   // pixels: fragments, integrals, subdivision (with its extra rays)
  size_t corner_rays = 0, extra_rays = 0;
  size_t subdivided_pixels = 0;
  FragmentStats fragments;
};

// The scene's ray-tracing state, built once and shared by frames: the Embree BVH, a summed-area
// table per raster texture and the integral of every texture (table or packed runs).
class TracedScene {
 public:
  // With a store, each raster texture's summed-area tables come from (or go to) the machine's
  // shared store and are used in place, so every server process builds them once per machine.
  // `stop` is asked before each texture's tables; a build stopped ends with CANCELLED. Without a
  // store the tables are built in this process: with `memory_budget` > 0 (the bytes uploads may
  // hold in memory, the server's --max-store-mb), tables that would pass it in all are refused
  // with RESOURCE_EXHAUSTED before any is built (their size follows from the textures').
  static absl::StatusOr<std::unique_ptr<TracedScene>> Build(
      const Scene& scene, std::shared_ptr<const SharedStore> store = nullptr,
      const StopRequested& stop = {}, uint64_t memory_budget = 0);

  // Renders settings.region of the settings.width x settings.height frame (empty: all of it) on
  // settings.threads threads (0: the caller's arena). `stop` is asked between tiles; a frame
  // stopped ends with CANCELLED. Texture filters do not apply: every texture
  // is integrated over the fragments (raster ones by their summed-area tables, packed vector ones
  // by the packed format's area integral).
  absl::StatusOr<RenderedFrame> Render(const Camera& camera, const RenderSettings& settings,
                                       const TraceOptions& options, TraceStats* stats = nullptr,
                                       const StopRequested& stop = {}) const;

  const Scene& scene() const { return scene_; }
  const RayScene& rays() const { return *rays_; }

 private:
  explicit TracedScene(const Scene& scene) : scene_(scene) {}
  const Scene& scene_;
  std::unique_ptr<RayScene> rays_;
  // Per scene texture (empty for none): the summed-area tables of its mip levels, the base first.
  std::vector<std::vector<std::shared_ptr<const SummedAreaTable>>> tables_;
  std::vector<std::unique_ptr<TextureIntegral>> integrals_;  // per scene texture, or null
  std::vector<std::shared_ptr<const StoreEntry>> entries_;   // the tables' mapped blocks
};

}  // namespace aperture
