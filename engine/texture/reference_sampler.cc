#include "texture/reference_sampler.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace aperture {

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
