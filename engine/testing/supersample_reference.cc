#include "testing/supersample_reference.h"

#include <tbb/parallel_for.h>

#include <cmath>
#include <limits>

#include "scene/shading.h"
#include "scene/spot_placement.h"
#include "texture/reference_sampler.h"
#include "trace/curved_intersect.h"
#include "trace/texture_mapping.h"

namespace aperture {
namespace {

class Sampler {
 public:
  Sampler(const Scene& scene, const RayScene& rays, const Camera& camera, int width, int height)
      : scene_(scene),
        rays_(rays),
        camera_(camera),
        width_(width),
        height_(height),
        frustum_(ResolveFrustum(camera, width, height)),
        orientation_(camera.Orientation()),
        t_far_(camera.far > 0 ? camera.far : std::numeric_limits<double>::infinity()),
        spots_(PlaceSpotLights(scene, camera.position)) {
    for (const CurvedPrimitive& c : scene.curved)
      mappings_.push_back({CurvedMapping(c, false), CurvedMapping(c, true)});
  }

  // The shaded colour seen through screen point (x, y).
  Rgba At(double x, double y) const {
    const Vec3 d = orientation_ * CameraRay(frustum_, width_, height_, x, y);
    const int primitive = rays_.Intersect(camera_.position, d, camera_.near, t_far_);
    const int polygons = static_cast<int>(scene_.polygons.size());
    const Rgba sky{scene_.sky.r, scene_.sky.g, scene_.sky.b, 1};
    if (primitive < 0) return sky;
    int material;
    double t, u, v;
    Vec3 normal;
    if (primitive < polygons) {
      const ScenePolygon& p = scene_.polygons[primitive];
      t = Dot(p.normal, p.vertices[0] - camera_.position) / Dot(p.normal, d);
      if (!(t > 0)) return sky;
      const Vec3 point = camera_.position + d * t;
      u = Dot(p.mapping.su, point) + p.mapping.u0;
      v = Dot(p.mapping.sv, point) + p.mapping.v0;
      normal = p.normal;
      material = p.material;
    } else {
      const CurvedPrimitive& c = scene_.curved[primitive - polygons];
      const auto hit = IntersectCurved(c, camera_.position, d, camera_.near, t_far_);
      if (!hit) return sky;
      const bool cap = hit->part == CurvedPart::kBottomCap || hit->part == CurvedPart::kTopCap;
      const PrimitiveMapping& m =
          cap ? mappings_[primitive - polygons].cap : mappings_[primitive - polygons].side;
      const TexPoint tp = m.f2.Apply(F1(m, hit->point));  // seed 003, eq. 2
      t = hit->t, u = tp.x, v = tp.z;
      normal = hit->normal;
      material = c.material;
    }
    if (Dot(normal, d) > 0) normal = -normal;
    const Material& mat = scene_.materials[material];
    Rgba colour = mat.base_color;
    if (mat.texture >= 0) {
      const SceneTexture& tex = *scene_.textures[mat.texture];
      colour =
          colour * BilinearPeriodic(tex.pyramid->level(0), u - std::floor(u), v - std::floor(v));
    }
    if (!mat.unlit) {
      Rgba light = SurfaceLight(scene_, mat, normal);
      for (const PlacedSpot& s : spots_)  // relative to the camera, as PlaceSpotLights gives them
        AddSpotLight(s, d * t, normal, scene_.fog_density, light);
      colour = colour * light;
    }
    colour = Fogged(scene_, colour, t * Length(d));
    colour.a = 1;
    return colour;
  }

 private:
  struct Slot {
    PrimitiveMapping side, cap;
  };
  const Scene& scene_;
  const RayScene& rays_;
  const Camera& camera_;
  int width_, height_;
  FrustumTangents frustum_;
  Mat3 orientation_;
  double t_far_;
  std::vector<PlacedSpot> spots_;
  std::vector<Slot> mappings_;
};

}  // namespace

Image RenderSupersampled(const Scene& scene, const RayScene& rays, const Camera& camera, int width,
                         int height, const SupersampleOptions& options) {
  const Sampler sampler(scene, rays, camera, width, height);
  Image out(width, height);
  const int n = std::max(1, options.samples);
  tbb::parallel_for(0, height, [&](int j) {
    for (int i = 0; i < width; ++i) {
      const uint64_t key = static_cast<uint64_t>(j) * width + i;
      double r = 0, g = 0, b = 0;
      for (int sy = 0; sy < n; ++sy)
        for (int sx = 0; sx < n; ++sx) {
          const double jx = options.jitter ? StratumJitter(key, sx, sy, 0) : 0.5;
          const double jy = options.jitter ? StratumJitter(key, sx, sy, 1) : 0.5;
          const Rgba c = sampler.At(i + (sx + jx) / n, j + (sy + jy) / n);
          r += c.r, g += c.g, b += c.b;
        }
      const double inv = 1.0 / (static_cast<double>(n) * n);
      out.at(i, j) = {static_cast<float>(r * inv), static_cast<float>(g * inv),
                      static_cast<float>(b * inv), 1.0f};
    }
  });
  return out;
}

}  // namespace aperture
