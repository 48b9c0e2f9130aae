// The samplers of a scene texture that need more than its mip-map: seed 000's table (aniso),
// OpenImageIO's TextureSystem (oiio) and the supersampled reference. Each is built on its first
// use, once, so scenes that never ask for them pay nothing.
#pragma once

#include <memory>
#include <mutex>

#include "texture/image.h"
#include "texture/prefiltered_table.h"
#include "texture/texture_sampler.h"

namespace aperture {

class FootprintSamplers {
 public:
  // `base`: the power-of-two texture (the pyramid's level 0); must outlive this object.
  explicit FootprintSamplers(const Image& base) : base_(base) {}
  ~FootprintSamplers();

  // The sampler for kAniso, kOiio or kReference; `fallback` (trilinear) when building the
  // table or the OpenImageIO copy fails (logged) or for any other mode.
  const TextureSampler& Get(FilterMode mode, const TextureSampler& fallback) const;

 private:
  const Image& base_;
  mutable std::once_flag aniso_once_, oiio_once_, reference_once_;
  mutable TableBlock table_;
  mutable std::unique_ptr<TextureSampler> aniso_, oiio_, reference_;
};

}  // namespace aperture
