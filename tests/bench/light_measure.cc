#include "light_measure.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "absl/strings/str_cat.h"
#include "render/frame_renderer.h"
#include "render/light_pass.h"
#include "scene/light_points.h"

namespace aperture {

double Luminance(const Rgba& c) { return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b; }

double Median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

FrameView::FrameView(const Camera& c, int w, int h)
    : camera(c),
      width(w),
      height(h),
      t(ResolveFrustum(c, w, h)),
      sx((t.right - t.left) / w),
      sy((t.top - t.bottom) / h),
      to_camera(c.Orientation().Transposed()) {}

bool SteadyWorldLight(const PointLight& light) {
  return light.flash.period_s == 0 && light.object < 0;
}

namespace {

// A footprint's radius for a share `s` of the light's energy of luminance `lum` per unit share,
// at least `least` pixels (docs/SCENE.md, "The footprint": the largest of half the minimum size,
// the lamp's projected radius and the bloom, at most kMaxFootprintPx).
double FootprintRadius(double lum, double least, double min_radius) {
  double r = std::max(min_radius, least);
  if (lum > kBloomEnergy) r = std::max(r, min_radius * std::pow(lum / kBloomEnergy, 0.25));
  return std::min(r, kMaxFootprintPx);
}

}  // namespace

LightView LookAt(const Scene& scene, const PointLight& light, const FrameView& v, double room_px) {
  LightView out;
  const Vec3 d = light.position - v.camera.position;
  const Vec3 p = v.to_camera * d;
  if (!(-p.z > v.camera.near)) return out;
  out.distance = Length(d);
  out.intensity_cd =
      LightIntensityTowards(light, d * (-1.0 / out.distance), 0, scene.lights.groups);
  if (!(out.intensity_cd > 0)) return out;
  out.drawn = true;
  const double tx = p.x / -p.z, ty = p.y / -p.z;
  out.x = (tx - v.t.left) / v.sx;
  out.y = (v.t.top - ty) / v.sy;
  // The solid angle of one pixel at (tx, ty): its tangent-plane area foreshortened.
  const double pixel_sr = v.sx * v.sy / std::pow(1 + tx * tx + ty * ty, 1.5);
  const double direct =
      scene.lights.settings.exposure * out.intensity_cd / (out.distance * out.distance) / pixel_sr;
  // Allard's law through the fog; the halo carries its forward share of the scattered rest.
  const double tau = scene.fog_density * out.distance;
  const double transmission = std::exp(-tau);
  const double halo_share = tau > 0 ? (1 - transmission) * kHaloForwardShare : 0;
  out.energy = direct * (transmission + halo_share);
  out.lamp_px = light.radius_m / out.distance / v.sy;
  const double min_radius = scene.lights.settings.min_size_px / 2;
  const double lum = direct * Luminance(light.color);
  out.footprint_px = FootprintRadius(lum * transmission, out.lamp_px, min_radius);
  if (halo_share > 0) {
    const double halo_least =
        std::max(2 * std::max(min_radius, out.lamp_px), Radians(kHaloDegPerTau * tau) / v.sy);
    out.footprint_px =
        std::max(out.footprint_px, FootprintRadius(lum * halo_share, halo_least, min_radius));
  }
  // The octagon's circumradius (1.0547 r), the filter's reach (a pixel) and a margin.
  const int half = static_cast<int>(std::ceil(std::max(1.06 * out.footprint_px, room_px))) + 3;
  const int cx = static_cast<int>(std::floor(out.x)), cy = static_cast<int>(std::floor(out.y));
  out.window = {cx - half, cy - half, cx + half + 1, cy + half + 1};
  out.inside = out.window.x0 >= 0 && out.window.y0 >= 0 && out.window.x1 <= v.width &&
               out.window.y1 <= v.height;
  return out;
}

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

ApertureLightProbe::ApertureLightProbe(const Scene& scene, const Scene& dark,
                                       const RenderSettings& settings)
    : lit_(scene), dark_(dark), settings_(settings) {}

absl::StatusOr<ApertureLightSample> ApertureLightProbe::Measure(const PointLight& light,
                                                                const Camera& camera,
                                                                const PixelRect& window,
                                                                bool whole_in_window) {
  lit_.lights.lights.assign(1, light);
  RenderSettings settings = settings_;
  settings.region = {std::max(0, window.x0), std::max(0, window.y0),
                     std::min(settings.width, window.x1), std::min(settings.height, window.y1)};
  if (settings.region.x1 <= settings.region.x0 || settings.region.y1 <= settings.region.y0)
    return ApertureLightSample{};  // wholly outside the frame
  auto with = RenderFrame(lit_, camera, settings);
  if (!with.ok()) return with.status();
  auto without = RenderFrame(dark_, camera, settings);
  if (!without.ok()) return without.status();
  const Image& a = with->image;
  const Image& b = without->image;
  std::vector<double> luminance(static_cast<size_t>(a.width()) * a.height());
  for (int y = 0; y < a.height(); ++y)
    for (int x = 0; x < a.width(); ++x)
      luminance[static_cast<size_t>(y) * a.width() + x] =
          Luminance(a.at(x, y)) - Luminance(b.at(x, y));
  ApertureLightSample out;
  out.image = ImageOf(luminance, settings.region);
  out.occluded = with->stats.lights_hidden + with->stats.lights_partly_hidden > 0;
  if (whole_in_window && out.image.at_border)
    return absl::InternalError(absl::StrCat(
        "the image of the light at (", light.position.x, ", ", light.position.y, ", ",
        light.position.z, ") reaches the border of its window [", window.x0, ", ", window.x1,
        ") x [", window.y0, ", ", window.y1, "): the window is too small to hold it"));
  return out;
}

PeerLight PeerLightOf(const PointLight& light, const LightView& lv, const Vec3& eye,
                      double min_size) {
  const std::vector<SizedPoint> sizes =
      OsgSimPointSizes(lv.lamp_px * std::sqrt(lv.intensity_cd / 1000), min_size);
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

}  // namespace aperture
