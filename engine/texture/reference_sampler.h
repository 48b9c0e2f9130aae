// The reference filter: the footprint's parallelogram aperture integrated by dense stratified
// supersampling of the bilinear-reconstructed full-resolution texture (box filter, periodic).
#pragma once

#include "base/image.h"
#include "texture/texture_sampler.h"

namespace aperture {

// Bilinear reconstruction of a periodic power-of-two image; texel centres at +0.5 (DESIGN.md).
Rgba BilinearPeriodic(const Image& image, double u, double v);

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
double StratumJitter(uint64_t key, uint32_t i, uint32_t j, uint32_t axis);

}  // namespace aperture
