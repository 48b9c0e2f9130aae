// A batch of texture footprints as arrays (one per field), the layout SIMD kernels load: the
// renderer fills one per run of pixels, a sampler filters it (TextureSampler::SampleBatch).
#pragma once

#include "texture/texture_sampler.h"

namespace aperture {

struct FootprintBatch {
  static constexpr int kMax = 64;
  int count = 0;
  // Left uninitialised: a batch is written before it is read, and zeroing it per run of pixels
  // was measurable.
  alignas(32) double u[kMax];
  alignas(32) double v[kMax];
  alignas(32) float dudx[kMax];
  alignas(32) float dvdx[kMax];
  alignas(32) float dudy[kMax];
  alignas(32) float dvdy[kMax];

  void Set(int i, const TextureFootprint& f) {
    u[i] = f.u, v[i] = f.v;
    dudx[i] = f.dudx, dvdx[i] = f.dvdx, dudy[i] = f.dudy, dvdy[i] = f.dvdy;
  }
  TextureFootprint At(int i) const { return {u[i], v[i], dudx[i], dvdx[i], dudy[i], dvdy[i]}; }
};

}  // namespace aperture
