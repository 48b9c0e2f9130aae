// Shading of one polygon at one pixel centre: perspective-correct texture coordinates and their
// derivatives (seed 000, eq. 1-2; render/footprint_kernels.h), the texture filter, Lambert sun plus
// ambient, spot lights per pixel (scene/spot_lights.h), distance fog.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "absl/status/statusor.h"
#include "raster/projection.h"
#include "render/footprint_kernels.h"
#include "scene/scene.h"
#include "scene/spot_lights.h"
#include "texture/texture_sampler.h"

namespace aperture {

struct ShadingOptions {
  bool override_filter = false;
  FilterMode filter = FilterMode::kTrilinear;
  double texture_aperture = 2.0;  // a: derivatives are scaled by it (DESIGN.md fairness rule)
};

class PolygonShader {
 public:
  // The shader of a frame: each material's texture filter (its own, or options.filter over all)
  // is built here if it was not yet (`stop` can stop a table's build part-way). An error naming
  // the material, the texture and the filter when a filter cannot be built.
  static absl::StatusOr<PolygonShader> Create(const Scene& scene, const FrameGeometry& geometry,
                                              const ShadingOptions& options,
                                              const std::function<bool()>& stop = nullptr);

  // Colour of polygon `index` at screen point (x, y) (a pixel centre), which may lie outside the
  // polygon: then its plane is extrapolated, as seed 002 takes each colour constant over the
  // aperture. Its alpha is Material::ShadedAlpha of the material's there (1 when opaque); the
  // colour is not premultiplied by it.
  Rgba Shade(int index, double x, double y) const;
  // out[i] = Shade(index, x0 + i, y) for i < count (a run of pixel centres of one row), with the
  // texture sampled in batches (TextureSampler::SampleMany).
  void ShadeRow(int index, double x0, double y, int count, Rgba* out) const;
  // out[i] = Shade(index, points[i].x, points[i].y) for i < count, likewise batched.
  void ShadeMany(int index, const Vec2* points, int count, Rgba* out) const;
  // Whether polygon `index` has one colour all over (untextured, no fog, no spot light on it):
  // then Shade gives FlatColour(index) at every point, bit for bit, and a renderer may skip the
  // batches.
  bool IsFlat(int index) const {
    return !(scene_.fog_density > 0) &&
           materials_[geo_.polygons[index].material].sampler == nullptr && SpotMask(index) == 0;
  }
  Rgba FlatColour(int index) const {
    return Finish(index, materials_[geo_.polygons[index].material].base, 0, 0, 0);
  }

 private:
  double InvDepth(int index, double x, double y) const;
  // Light and fog on the (textured) surface colour of polygon `index` at (x, y), inverse depth w.
  Rgba Finish(int index, Rgba colour, double w, double x, double y) const;
  // Which of spots_ may light polygon `index` (bit k: spots_[k]); 0 when none can.
  uint32_t SpotMask(int index) const { return spot_masks_.empty() ? 0 : spot_masks_[index]; }
  // spot_masks_, from the polygons' extents and the spots' cones.
  void MaskSpots(const FrameGeometry& geometry);
  // The light the spots in `mask` add at (x, y), inverse depth w, of polygon `p`.
  void AddSpots(const ScreenPolygon& p, uint32_t mask, double w, double x, double y,
                Rgba& light) const;
  // Shades point_at(i), i < count, in batches whose footprints fill_footprints computes.
  template <typename PointAt, typename FillFootprints>
  void ShadeBatched(int index, int count, PointAt point_at, FillFootprints fill_footprints,
                    Rgba* out) const;

  struct MaterialState {
    Rgba base;
    const TextureSampler* sampler;  // null: untextured
    const Material* material;
    bool unpremultiply;  // the texture's colours are premultiplied by its alpha
  };
  PolygonShader(const Scene& scene, const FrameGeometry& geometry, const ShadingOptions& options,
                std::vector<MaterialState> materials);
  // The material's colour and alpha over a filtered texel.
  static Rgba Surface(const MaterialState& mat, Rgba texel) {
    if (mat.unpremultiply) {
      const float k = texel.a > 0 ? 1.0f / texel.a : 0.0f;
      texel.r *= k, texel.g *= k, texel.b *= k;
    }
    return mat.base * texel;
  }

  const Scene& scene_;
  const FrameGeometry& geo_;
  double aperture_;
  RowFootprintsFn row_footprints_;  // the interior's kernel (render/footprint_kernels.h)
  std::vector<MaterialState> materials_;
  std::vector<double> min_inv_depth_;  // per polygon: over its vertices, to keep extrapolation sane
  std::vector<PlacedSpot> spots_;      // this frame's, in camera space
  std::vector<uint16_t> spot_masks_;   // per polygon (SpotMask); empty without spots
  static_assert(kMaxSpotLights <= 16, "spot_masks_ holds a bit per spot light");
};

}  // namespace aperture
