#include "texture/texture_sampler.h"

#include "texture/footprint_batch.h"

namespace aperture {

void TextureSampler::SampleBatch(const FootprintBatch& in, Rgba* out) const {
  union Scratch {  // uninitialised: every element used is written first
    Scratch() {}
    TextureFootprint f[FootprintBatch::kMax];
  } scratch;
  TextureFootprint* footprints = scratch.f;
  for (int i = 0; i < in.count; ++i) footprints[i] = in.At(i);
  SampleMany(footprints, out, in.count);
}

}  // namespace aperture
