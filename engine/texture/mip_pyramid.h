// An isotropic mip-map pyramid of a periodic power-of-two texture (the H = L diagonal of seed
// 000's table), with the nearest, bilinear and trilinear samplers over it.
#pragma once

#include <vector>

#include "base/image.h"
#include "texture/texture_sampler.h"

namespace aperture {

class MipPyramid {
 public:
  // `base` must be a power of two per side (see ResizeToPowerOfTwo).
  explicit MipPyramid(Image base);

  int levels() const { return static_cast<int>(levels_.size()); }
  const Image& level(int i) const { return levels_[i]; }

  // Periodic texel fetch on level `l`.
  const Rgba& Texel(int l, int x, int y) const {
    const Image& img = levels_[l];
    return img.at(x & (img.width() - 1), y & (img.height() - 1));
  }
  Rgba Nearest(double u, double v) const;
  // Bilinear reconstruction on level `l`; texel centres at +0.5 (DESIGN.md).
  Rgba Bilinear(int l, double u, double v) const;
  // Isotropic trilinear: level from the longer footprint axis.
  Rgba Trilinear(const TextureFootprint& f) const;

 private:
  std::vector<Image> levels_;
};

class NearestSampler final : public TextureSampler {
 public:
  explicit NearestSampler(const MipPyramid& p) : pyramid_(p) {}
  Rgba Sample(const TextureFootprint& f) const override { return pyramid_.Nearest(f.u, f.v); }
  // The batch in one loop, the pyramid's code inlined (no virtual call per sample).
  void SampleMany(const TextureFootprint* in, Rgba* out, int count) const override;

 private:
  const MipPyramid& pyramid_;
};

class BilinearSampler final : public TextureSampler {
 public:
  explicit BilinearSampler(const MipPyramid& p) : pyramid_(p) {}
  Rgba Sample(const TextureFootprint& f) const override { return pyramid_.Bilinear(0, f.u, f.v); }
  // The batch in one loop, the pyramid's code inlined (no virtual call per sample).
  void SampleMany(const TextureFootprint* in, Rgba* out, int count) const override;

 private:
  const MipPyramid& pyramid_;
};

class TrilinearSampler final : public TextureSampler {
 public:
  explicit TrilinearSampler(const MipPyramid& p) : pyramid_(p) {}
  Rgba Sample(const TextureFootprint& f) const override { return pyramid_.Trilinear(f); }
  // The batch in one loop, the pyramid's code inlined (no virtual call per sample).
  void SampleMany(const TextureFootprint* in, Rgba* out, int count) const override;
  // Through the fastest kernel of texture/trilinear_kernels.h: the same floats.
  void SampleBatch(const FootprintBatch& in, Rgba* out) const override;

 private:
  const MipPyramid& pyramid_;
};

}  // namespace aperture
