#include "texture/reference_sampler.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace aperture {

Rgba BilinearPeriodic(const Image& image, double u, double v) {
  const int w = image.width(), h = image.height();
  const double x = u * w - 0.5, y = v * h - 0.5;
  const double fx0 = std::floor(x), fy0 = std::floor(y);
  const float fx = static_cast<float>(x - fx0), fy = static_cast<float>(y - fy0);
  const int x0 = static_cast<int>(fx0) & (w - 1), y0 = static_cast<int>(fy0) & (h - 1);
  const int x1 = (x0 + 1) & (w - 1), y1 = (y0 + 1) & (h - 1);
  const Rgba& a = image.at(x0, y0);
  const Rgba& b = image.at(x1, y0);
  const Rgba& c = image.at(x0, y1);
  const Rgba& d = image.at(x1, y1);
  return (a * (1 - fx) + b * fx) * (1 - fy) + (c * (1 - fx) + d * fx) * fy;
}

double StratumJitter(uint64_t key, uint32_t i, uint32_t j, uint32_t axis) {
  // SplitMix64 of the stratum's coordinates.
  uint64_t z = key * 0x9E3779B97F4A7C15ull + (uint64_t{i} << 32 | j) * 0xBF58476D1CE4E5B9ull +
               axis * 0x94D049BB133111EBull;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  z ^= z >> 31;
  return static_cast<double>(z >> 11) * 0x1.0p-53;
}

Rgba ReferenceSampler::Sample(const TextureFootprint& f) const {
  const double w = image_.width(), h = image_.height();
  auto strata = [&](double du, double dv) {
    const double texels = std::hypot(du * w, dv * h);
    return std::clamp(static_cast<int>(std::ceil(texels * density_)), 2, max_per_side_);
  };
  const int nx = strata(f.dudx, f.dvdx), ny = strata(f.dudy, f.dvdy);
  uint64_t key = 0;
  std::memcpy(&key, &f.u, sizeof(key));
  key ^= static_cast<uint64_t>(std::hash<double>{}(f.v));
  double r = 0, g = 0, b = 0, a = 0;
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const double s = (i + StratumJitter(key, i, j, 0)) / nx - 0.5;
      const double t = (j + StratumJitter(key, i, j, 1)) / ny - 0.5;
      const Rgba c =
          BilinearPeriodic(image_, f.u + s * f.dudx + t * f.dudy, f.v + s * f.dvdx + t * f.dvdy);
      r += c.r, g += c.g, b += c.b, a += c.a;
    }
  }
  const double inv = 1.0 / (static_cast<double>(nx) * ny);
  return {static_cast<float>(r * inv), static_cast<float>(g * inv), static_cast<float>(b * inv),
          static_cast<float>(a * inv)};
}

}  // namespace aperture
