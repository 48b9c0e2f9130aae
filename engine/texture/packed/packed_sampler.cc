#include "texture/packed/packed_sampler.h"

#include <algorithm>
#include <cmath>

namespace aperture::packed {
namespace {

// Texel coordinate of a periodic texture coordinate: floor(frac(t) * n), clamped.
uint32_t Wrap(double t, uint32_t n) {
  double f = t - std::floor(t);
  const double texel = std::floor(f * n);
  if (!(texel >= 0)) return 0;  // NaN
  return static_cast<uint32_t>(std::min<double>(texel, n - 1));
}

Rgba ToRgba(uint32_t colour) {
  return {Channel(colour, 0) / 255.0f, Channel(colour, 1) / 255.0f, Channel(colour, 2) / 255.0f,
          Channel(colour, 3) / 255.0f};
}

}  // namespace

PackedTextureSampler::PackedTextureSampler(const PackedTextureView& texture, PackedSampling mode)
    : texture_(texture), mode_(mode), index_(texture), area_(texture, &index_) {}

Rgba PackedTextureSampler::Nearest(double u, double v) const {
  return ToRgba(index_.ColorAt(Wrap(u, texture_.width()), Wrap(v, texture_.height())));
}

Rgba PackedTextureSampler::AreaMean(double u0, double v0, double u1, double v1) const {
  const double w = texture_.width(), h = texture_.height();
  if (!(u1 > u0) || !(v1 > v0)) return Nearest(u0, v0);
  // Whole periods far from the origin: shift so the integral sees small coordinates.
  const double su = std::floor(u0), sv = std::floor(v0);
  const double x0 = (u0 - su) * w, y0 = (v0 - sv) * h, x1 = (u1 - su) * w, y1 = (v1 - sv) * h;
  // Within one texel the mean is that texel's colour: one run lookup instead of the descent
  // (most footprints near a low camera are a fraction of a texel).
  if (std::floor(x0) == std::ceil(x1) - 1 && std::floor(y0) == std::ceil(y1) - 1)
    return Nearest(0.5 * (u0 + u1), 0.5 * (v0 + v1));
  const AreaSum s = area_.Integrate(x0, y0, x1, y1);
  if (!(s.area > 0)) return Nearest(u0, v0);
  const double k = 1.0 / (255.0 * s.area);
  return {static_cast<float>(s.channels[0] * k), static_cast<float>(s.channels[1] * k),
          static_cast<float>(s.channels[2] * k), static_cast<float>(s.channels[3] * k)};
}

Rgba PackedTextureSampler::Sample(const TextureFootprint& f) const {
  if (mode_ == PackedSampling::kNearest) return Nearest(f.u, f.v);
  const double half_u = 0.5 * (std::fabs(f.dudx) + std::fabs(f.dudy));
  const double half_v = 0.5 * (std::fabs(f.dvdx) + std::fabs(f.dvdy));
  double u0 = f.u - half_u, v0 = f.v - half_v, u1 = f.u + half_u, v1 = f.v + half_v;
  // A footprint many texels across (far away, at grazing angles) costs the integral's descent
  // along its whole perimeter in texels. Its edges are moved to the nearest multiple of an aligned
  // block at most 1/8 of its shorter side, so the descent stops at blocks of that size: the cost
  // falls with the footprint's size, and the rectangle (itself the footprint's bounding box) grows
  // or shrinks by at most 1/8 of its area.
  const double w = texture_.width(), h = texture_.height();
  const double shorter = std::min((u1 - u0) * w, (v1 - v0) * h);
  if (shorter >= 16) {
    const double block = std::exp2(std::floor(std::log2(shorter / 8)));
    auto snap = [&](double t, double size) { return std::round(t * size / block) * block / size; };
    u0 = snap(u0, w), u1 = snap(u1, w), v0 = snap(v0, h), v1 = snap(v1, h);
  }
  return AreaMean(u0, v0, u1, v1);
}

void PackedTextureSampler::SampleMany(const TextureFootprint* in, Rgba* out, int count) const {
  if (mode_ != PackedSampling::kNearest) return TextureSampler::SampleMany(in, out, count);
  constexpr int kChunk = 256;
  uint32_t xs[kChunk], ys[kChunk], colours[kChunk];
  for (int begin = 0; begin < count; begin += kChunk) {
    const int n = std::min(kChunk, count - begin);
    for (int i = 0; i < n; ++i) {
      xs[i] = Wrap(in[begin + i].u, texture_.width());
      ys[i] = Wrap(in[begin + i].v, texture_.height());
    }
    const size_t size = static_cast<size_t>(n);
    index_.ColorsAt({xs, size}, {ys, size}, {colours, size});
    for (int i = 0; i < n; ++i) out[begin + i] = ToRgba(colours[i]);
  }
}

}  // namespace aperture::packed
