#include "render/polygon_shader.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "absl/strings/str_cat.h"
#include "render/footprint_kernels.h"
#include "scene/shading.h"

namespace aperture {

absl::StatusOr<PolygonShader> PolygonShader::Create(const Scene& scene,
                                                    const FrameGeometry& geometry,
                                                    const ShadingOptions& options,
                                                    const std::function<bool()>& stop) {
  std::vector<MaterialState> materials;
  materials.reserve(scene.materials.size());
  for (const Material& m : scene.materials) {
    MaterialState state{m.base_color, nullptr, &m, false};
    if (m.texture >= 0) {
      const SceneTexture& texture = *scene.textures[m.texture];
      state.unpremultiply = texture.has_alpha;
      const FilterMode mode = options.override_filter ? options.filter : m.filter;
      auto sampler = texture.Sampler(mode, stop);
      if (!sampler.ok())
        return absl::Status(sampler.status().code(),
                            absl::StrCat("materials ('", m.id, "'): ", sampler.status().message()));
      state.sampler = *sampler;
    }
    materials.push_back(state);
  }
  return PolygonShader(scene, geometry, options, std::move(materials));
}

PolygonShader::PolygonShader(const Scene& scene, const FrameGeometry& geometry,
                             const ShadingOptions& options, std::vector<MaterialState> materials)
    : scene_(scene),
      geo_(geometry),
      aperture_(options.texture_aperture),
      row_footprints_(BestRowFootprints()),
      materials_(std::move(materials)) {
  min_inv_depth_.resize(geometry.polygons.size());
  tbb::parallel_for(tbb::blocked_range<size_t>(0, geometry.polygons.size(), 4096),
                    [&](const tbb::blocked_range<size_t>& range) {
                      for (size_t i = range.begin(); i < range.end(); ++i) {
                        const ScreenPolygon& p = geometry.polygons[i];
                        double w = INFINITY;
                        for (const Vec2& v : p.vertices) w = std::min(w, p.inv_depth.At(v.x, v.y));
                        min_inv_depth_[i] = w;
                      }
                    });
}

double PolygonShader::InvDepth(int index, double x, double y) const {
  return InvDepthAt(geo_.polygons[index], min_inv_depth_[index], x, y);
}

Rgba PolygonShader::Finish(const ScreenPolygon& p, Rgba colour, double w, double x,
                           double y) const {
  const float alpha = materials_[p.material].material->ShadedAlpha(colour.a);
  colour = colour * p.light;
  if (scene_.fog_density > 0) colour = Fogged(scene_, colour, Length(geo_.Ray(x, y)) / w);
  colour.a = alpha;
  return colour;
}

Rgba PolygonShader::Shade(int index, double x, double y) const {
  const ScreenPolygon& p = geo_.polygons[index];
  const MaterialState& mat = materials_[p.material];
  const double w = InvDepth(index, x, y);
  Rgba colour = mat.base;
  if (mat.sampler != nullptr)
    colour = Surface(mat, mat.sampler->Sample(FootprintAt(p, aperture_, w, x, y)));
  return Finish(p, colour, w, x, y);
}

template <typename PointAt, typename FillFootprints>
void PolygonShader::ShadeBatched(int index, int count, PointAt point_at,
                                 FillFootprints fill_footprints, Rgba* out) const {
  const ScreenPolygon& p = geo_.polygons[index];
  const MaterialState& mat = materials_[p.material];
  if (mat.sampler == nullptr) {
    for (int i = 0; i < count; ++i) {
      const Vec2 q = point_at(i);
      out[i] = Shade(index, q.x, q.y);
    }
    return;
  }
  constexpr int kBatch = FootprintBatch::kMax;
  // Scratch left uninitialised: zeroing it cost an eighth of an interior pixel's shading.
  FootprintBatch footprints;
  union Texels {
    Texels() {}
    Rgba texels[kBatch];
  } sampled;
  Rgba* texels = sampled.texels;
  double inv_depths[kBatch];
  const bool fog = scene_.fog_density > 0;
  for (int first = 0; first < count; first += kBatch) {
    const int n = std::min(kBatch, count - first);
    fill_footprints(p, first, n, footprints, inv_depths);
    mat.sampler->SampleBatch(footprints, texels);
    if (fog) {
      for (int i = 0; i < n; ++i) {
        const Vec2 q = point_at(first + i);
        out[first + i] = Finish(p, Surface(mat, texels[i]), inv_depths[i], q.x, q.y);
      }
      continue;
    }
    for (int i = 0; i < n; ++i) {  // Finish without fog, inlined: the same operations
      Rgba colour = Surface(mat, texels[i]);
      const float alpha = mat.material->ShadedAlpha(colour.a);
      colour = colour * p.light;
      colour.a = alpha;
      out[first + i] = colour;
    }
  }
}

void PolygonShader::ShadeRow(int index, double x0, double y, int count, Rgba* out) const {
  ShadeBatched(
      index, count,
      [&](int i) {
        return Vec2{x0 + i, y};
      },
      [&](const ScreenPolygon& p, int first, int n, FootprintBatch& footprints,
          double* inv_depths) {
        row_footprints_(p, min_inv_depth_[index], aperture_, RowRun{x0, y, first, n}, footprints,
                        inv_depths);
      },
      out);
}

void PolygonShader::ShadeMany(int index, const Vec2* points, int count, Rgba* out) const {
  ShadeBatched(
      index, count, [&](int i) { return points[i]; },
      [&](const ScreenPolygon& p, int first, int n, FootprintBatch& footprints,
          double* inv_depths) {
        for (int i = 0; i < n; ++i) {
          const Vec2 q = points[first + i];
          inv_depths[i] = InvDepth(index, q.x, q.y);
          footprints.Set(i, FootprintAt(p, aperture_, inv_depths[i], q.x, q.y));
        }
        footprints.count = n;
      },
      out);
}

}  // namespace aperture
