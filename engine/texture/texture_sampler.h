// The sampling interface every texture filter mode implements.
#pragma once

#include "base/image.h"

namespace aperture {

// kAniso: seed 000's prefiltered table; kOiio: OpenImageIO's TextureSystem (for comparison);
// kReference: the footprint integrated by dense supersampling (slow, for measurement).
enum class FilterMode { kNearest, kBilinear, kTrilinear, kAniso, kOiio, kReference };

const char* FilterModeName(FilterMode mode);

// Where and how wide one sample is. (u, v) in texture repeats (the texture is the unit square
// repeated periodically); derivatives in repeats per pixel, already multiplied by the filter
// aperture a (DESIGN.md: every mode is driven with the same aperture).
struct TextureFootprint {
  double u = 0, v = 0;
  float dudx = 0, dvdx = 0, dudy = 0, dvdy = 0;
};

struct FootprintBatch;  // texture/footprint_batch.h

class TextureSampler {
 public:
  virtual ~TextureSampler() = default;
  virtual Rgba Sample(const TextureFootprint& footprint) const = 0;
  // out[i] = Sample(in[i]) for i < count; a mode overrides it where a batch is faster.
  virtual void SampleMany(const TextureFootprint* in, Rgba* out, int count) const {
    for (int i = 0; i < count; ++i) out[i] = Sample(in[i]);
  }
  // out[i] = Sample(in.At(i)) for i < in.count: the renderer's batches. By default through
  // SampleMany; a mode with a SIMD kernel overrides it.
  virtual void SampleBatch(const FootprintBatch& in, Rgba* out) const;
};

}  // namespace aperture
