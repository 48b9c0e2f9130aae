// Sampling a packed vector texture the way the renderer asks: nearest texel at (u, v) in texture
// repeats, or the exact average over a rectangle (the "area" mode: seed 001's missing
// anti-aliasing; the rectangles seed 003's fragments will pass in). Implements TextureSampler so a
// scene can use an .apv texture once the scene builder knows the source type.
#pragma once

#include "texture/packed/area_integral.h"
#include "texture/packed/packed_texture.h"
#include "texture/packed/run_index.h"
#include "texture/texture_sampler.h"

namespace aperture::packed {

enum class PackedSampling { kNearest, kArea };

class PackedTextureSampler : public TextureSampler {
 public:
  // The view's bytes must outlive the sampler.
  PackedTextureSampler(const PackedTextureView& texture, PackedSampling mode);

  // Colour of the texel holding (u, v); the texture repeats with period 1 in u and v; u along
  // the width, v along the height (row 0 first). 8-bit values / 255, taken as linear.
  Rgba Nearest(double u, double v) const;
  // Mean colour over [u0, u1) x [v0, v1) in repeats (may wrap and span periods); a degenerate
  // rectangle gives Nearest(u0, v0).
  Rgba AreaMean(double u0, double v0, double u1, double v1) const;

  // kNearest: Nearest(u, v). kArea: AreaMean over the bounding rectangle of the footprint's
  // parallelogram (centre (u, v), edge vectors (dudx, dvdx) and (dudy, dvdy)).
  Rgba Sample(const TextureFootprint& footprint) const override;
  // kNearest reads the batch through RunIndex::ColorsAt; the same colours as Sample.
  void SampleMany(const TextureFootprint* in, Rgba* out, int count) const override;

  const PackedTextureView& texture() const { return texture_; }
  // The exact area integral (seed 003's fragments integrate through it in the raytrace mode).
  const AreaIntegrator& area() const { return area_; }

 private:
  PackedTextureView texture_;
  PackedSampling mode_;
  RunIndex index_;
  AreaIntegrator area_;
};

}  // namespace aperture::packed
