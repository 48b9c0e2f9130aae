#include "render/polygon_shader.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "absl/strings/str_cat.h"
#include "render/footprint_kernels.h"
#include "scene/shading.h"
#include "scene/spot_placement.h"

namespace aperture {
namespace {

// The plane of `p` in camera space as the vector g with dot(g, P) = 1 at its points, from its
// screen-linear inverse depth: 1/depth(x, y) = dot(g, Ray(x, y)) (raster/projection.h).
Vec3 PlaneOf(const FrameGeometry& geo, const ScreenPolygon& p) {
  const FrustumTangents& f = geo.frustum;
  const double sx = (f.right - f.left) / geo.width, sy = (f.top - f.bottom) / geo.height;
  const double gx = p.inv_depth.a / sx, gy = -p.inv_depth.b / sy;
  return {gx, gy, gx * f.left + gy * f.top - p.inv_depth.c};
}

}  // namespace

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
  spots_ = PlaceSpotLights(scene, geometry.camera_position);
  if (spots_.empty()) return;
  for (PlacedSpot& s : spots_) {
    s.position = geometry.to_camera * s.position;
    s.axis = geometry.to_camera * s.axis;
  }
  MaskSpots(geometry);
}

void PolygonShader::MaskSpots(const FrameGeometry& geometry) {
  spot_masks_.assign(geometry.polygons.size(), 0);
  // A pixel's shading point may lie up to the filter's reach beyond the polygon (its plane
  // extrapolated): its bounding sphere is grown by this many pixels at its far depth.
  constexpr double kReachPx = 4;
  const double px = std::max((geometry.frustum.right - geometry.frustum.left) / geometry.width,
                             (geometry.frustum.top - geometry.frustum.bottom) / geometry.height);
  std::vector<double> sin_outer(spots_.size());
  for (size_t k = 0; k < spots_.size(); ++k)
    sin_outer[k] = std::sqrt(std::max(0.0, 1 - spots_[k].cos_outer * spots_[k].cos_outer));
  tbb::parallel_for(
      tbb::blocked_range<size_t>(0, geometry.polygons.size(), 4096),
      [&](const tbb::blocked_range<size_t>& range) {
        for (size_t i = range.begin(); i < range.end(); ++i) {
          const ScreenPolygon& p = geometry.polygons[i];
          if (materials_[p.material].material->unlit || p.vertices.empty()) continue;
          // The polygon's vertices in camera space, their centre and the sphere around them.
          Vec3 centre{0, 0, 0};
          double far = 0;
          for (const Vec2& v : p.vertices) {
            const double w = std::max(p.inv_depth.At(v.x, v.y), min_inv_depth_[i]);
            centre = centre + geometry.Ray(v.x, v.y) * (1 / w);
            far = std::max(far, 1 / w);
          }
          centre = centre * (1.0 / static_cast<double>(p.vertices.size()));
          double radius = 0;
          for (const Vec2& v : p.vertices) {
            const double w = std::max(p.inv_depth.At(v.x, v.y), min_inv_depth_[i]);
            radius = std::max(radius, Length(geometry.Ray(v.x, v.y) * (1 / w) - centre));
          }
          radius += kReachPx * px * far * Length(geometry.Ray(0, 0));
          const Vec3 plane = PlaneOf(geometry, p);  // dot(plane, P) = 1 on it
          uint16_t mask = 0;
          for (size_t k = 0; k < spots_.size(); ++k) {
            const PlacedSpot& s = spots_[k];
            // The lamp on the far side of the plane lights the side the camera does not see.
            if (!(Dot(plane, s.position) < 1)) continue;
            // The sphere against the cone (trig-free: the distance from the centre to the cone's
            // surface, valid for half-angles below 90 degrees; conservative behind the apex).
            const Vec3 v = centre - s.position;
            const double along = Dot(v, s.axis), v2 = Dot(v, v);
            const bool reaches =
                v2 <= radius * radius ||
                (along >= -radius && s.cos_outer * std::sqrt(std::max(0.0, v2 - along * along)) -
                                             along * sin_outer[k] <=
                                         radius);
            if (reaches) mask |= static_cast<uint16_t>(1u << k);
          }
          spot_masks_[i] = mask;
        }
      });
}

void PolygonShader::AddSpots(const ScreenPolygon& p, uint32_t mask, double w, double x, double y,
                             Rgba& light) const {
  const Vec3 plane = PlaneOf(geo_, p);
  const Vec3 facing = Normalize(plane) * -1.0;  // towards the camera's side
  const Vec3 at = geo_.Ray(x, y) * (1 / w);
  for (size_t k = 0; mask != 0; ++k, mask >>= 1)
    if (mask & 1) AddSpotLight(spots_[k], at, facing, scene_.fog_density, light);
}

double PolygonShader::InvDepth(int index, double x, double y) const {
  return InvDepthAt(geo_.polygons[index], min_inv_depth_[index], x, y);
}

Rgba PolygonShader::Finish(int index, Rgba colour, double w, double x, double y) const {
  const ScreenPolygon& p = geo_.polygons[index];
  const float alpha = materials_[p.material].material->ShadedAlpha(colour.a);
  if (const uint32_t mask = SpotMask(index); mask != 0) {
    Rgba light = p.light;
    AddSpots(p, mask, w, x, y, light);
    colour = colour * light;
  } else {
    colour = colour * p.light;
  }
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
  return Finish(index, colour, w, x, y);
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
  // Fog and spot lights vary over the polygon: the general Finish per point.
  const bool varies = scene_.fog_density > 0 || SpotMask(index) != 0;
  for (int first = 0; first < count; first += kBatch) {
    const int n = std::min(kBatch, count - first);
    fill_footprints(p, first, n, footprints, inv_depths);
    mat.sampler->SampleBatch(footprints, texels);
    if (varies) {
      for (int i = 0; i < n; ++i) {
        const Vec2 q = point_at(first + i);
        out[first + i] = Finish(index, Surface(mat, texels[i]), inv_depths[i], q.x, q.y);
      }
      continue;
    }
    for (int i = 0; i < n; ++i) {  // Finish without fog or spots, inlined: the same operations
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
