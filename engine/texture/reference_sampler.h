// The reference filter: the footprint's parallelogram aperture integrated by dense stratified
// supersampling of the bilinear-reconstructed full-resolution texture (box filter, periodic).
#pragma once

#include <cmath>
#include <cstdint>

#include "base/image.h"
#include "texture/texture_sampler.h"

namespace aperture {

// Bilinear reconstruction of a periodic power-of-two image; texel centres at +0.5 (DESIGN.md).
// Inline: the references call it for every one of their samples.
inline Rgba BilinearPeriodic(const Image& image, double u, double v) {
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

class ReferenceSampler final : public TextureSampler {
 public:
  // `samples_per_texel` strata per texel of footprint extent, per side, between 2 and
  // `max_per_side`. The image must outlive the sampler.
  explicit ReferenceSampler(const Image& image, double samples_per_texel = 2.0,
                            int max_per_side = 256)
      : image_(image), density_(samples_per_texel), max_per_side_(max_per_side) {}
  // The parallelogram (u, v) + s (dudx, dvdx) + t (dudy, dvdy), s, t in [-1/2, 1/2].
  Rgba Sample(const TextureFootprint& f) const override;

 private:
  const Image& image_;
  double density_;
  int max_per_side_;
};

// A deterministic jitter in [0, 1) for stratum (i, j) of sample `key`.
inline double StratumJitter(uint64_t key, uint32_t i, uint32_t j, uint32_t axis) {
  // SplitMix64 of the stratum's coordinates.
  uint64_t z = key * 0x9E3779B97F4A7C15ull + (uint64_t{i} << 32 | j) * 0xBF58476D1CE4E5B9ull +
               axis * 0x94D049BB133111EBull;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  z ^= z >> 31;
  return static_cast<double>(z >> 11) * 0x1.0p-53;
}

}  // namespace aperture
