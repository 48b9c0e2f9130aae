#include "render/polygon_shader.h"

#include <algorithm>
#include <cmath>

namespace aperture {

PolygonShader::PolygonShader(const Scene& scene, const FrameGeometry& geometry,
                             const ShadingOptions& options)
    : scene_(scene), geo_(geometry), aperture_(options.texture_aperture) {
  for (const Material& m : scene.materials) {
    MaterialState state{m.base_color, nullptr};
    if (m.texture >= 0) {
      const FilterMode mode = options.override_filter ? options.filter : m.filter;
      state.sampler = &scene.textures[m.texture]->Sampler(mode);
    }
    materials_.push_back(state);
  }
  min_inv_depth_.reserve(geometry.polygons.size());
  for (const ScreenPolygon& p : geometry.polygons) {
    double w = INFINITY;
    for (const Vec2& v : p.vertices) w = std::min(w, p.inv_depth.At(v.x, v.y));
    min_inv_depth_.push_back(w);
  }
}

double PolygonShader::InvDepth(int index, double x, double y) const {
  return std::max(geo_.polygons[index].inv_depth.At(x, y), min_inv_depth_[index]);
}

TextureFootprint PolygonShader::Footprint(const ScreenPolygon& p, double w, double x,
                                          double y) const {
  // seed 000, eq. 1: U = (A_u x + B_u y + C_u) / (A_z x + B_z y + C_z).
  const double inv_w = 1.0 / w;
  const double u = p.u_num.At(x, y) * inv_w, v = p.v_num.At(x, y) * inv_w;
  // seed 000, eq. 2: dU/dx = (A_u - A_z U) / z0, scaled by the aperture a.
  const double s = aperture_ * inv_w;
  TextureFootprint f;
  f.u = u - std::floor(u);
  f.v = v - std::floor(v);
  f.dudx = static_cast<float>((p.u_num.a - p.inv_depth.a * u) * s);
  f.dvdx = static_cast<float>((p.v_num.a - p.inv_depth.a * v) * s);
  f.dudy = static_cast<float>((p.u_num.b - p.inv_depth.b * u) * s);
  f.dvdy = static_cast<float>((p.v_num.b - p.inv_depth.b * v) * s);
  return f;
}

Rgba PolygonShader::Finish(const ScreenPolygon& p, Rgba colour, double w, double x,
                           double y) const {
  colour = colour * p.light;
  if (scene_.fog_density > 0) {
    const double distance = Length(geo_.Ray(x, y)) / w;
    const float keep = static_cast<float>(std::exp(-scene_.fog_density * distance));
    colour = colour * keep + scene_.fog_color * (1.0f - keep);
  }
  colour.a = 1.0f;
  return colour;
}

Rgba PolygonShader::Shade(int index, double x, double y) const {
  const ScreenPolygon& p = geo_.polygons[index];
  const MaterialState& mat = materials_[p.material];
  const double w = InvDepth(index, x, y);
  Rgba colour = mat.base;
  if (mat.sampler != nullptr) colour = colour * mat.sampler->Sample(Footprint(p, w, x, y));
  return Finish(p, colour, w, x, y);
}

template <typename PointAt>
void PolygonShader::ShadeBatched(int index, int count, PointAt point_at, Rgba* out) const {
  const ScreenPolygon& p = geo_.polygons[index];
  const MaterialState& mat = materials_[p.material];
  if (mat.sampler == nullptr) {
    for (int i = 0; i < count; ++i) {
      const Vec2 q = point_at(i);
      out[i] = Shade(index, q.x, q.y);
    }
    return;
  }
  constexpr int kBatch = 64;
  // Scratch left uninitialised: zeroing it (the members' default initialisers) cost an eighth of
  // an interior pixel's shading.
  union Scratch {
    Scratch() {}
    TextureFootprint footprints[kBatch];
  } scratch;
  union Texels {
    Texels() {}
    Rgba texels[kBatch];
  } sampled;
  TextureFootprint* footprints = scratch.footprints;
  Rgba* texels = sampled.texels;
  double inv_depths[kBatch];
  const bool fog = scene_.fog_density > 0;
  for (int first = 0; first < count; first += kBatch) {
    const int n = std::min(kBatch, count - first);
    for (int i = 0; i < n; ++i) {
      const Vec2 q = point_at(first + i);
      inv_depths[i] = InvDepth(index, q.x, q.y);
      footprints[i] = Footprint(p, inv_depths[i], q.x, q.y);
    }
    mat.sampler->SampleMany(footprints, texels, n);
    if (fog) {
      for (int i = 0; i < n; ++i) {
        const Vec2 q = point_at(first + i);
        out[first + i] = Finish(p, mat.base * texels[i], inv_depths[i], q.x, q.y);
      }
      continue;
    }
    for (int i = 0; i < n; ++i) {  // Finish without fog, inlined: the same operations
      Rgba colour = (mat.base * texels[i]) * p.light;
      colour.a = 1.0f;
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
      out);
}

void PolygonShader::ShadeMany(int index, const Vec2* points, int count, Rgba* out) const {
  ShadeBatched(
      index, count, [&](int i) { return points[i]; }, out);
}

}  // namespace aperture
