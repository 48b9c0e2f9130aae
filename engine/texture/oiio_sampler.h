// OpenImageIO's TextureSystem as a filter mode, for comparison: a maketx-style tiled, mip-mapped
// copy of the texture, looked up with OpenImageIO's default options (anisotropic 32, smart
// bicubic) or others (OiioOptions) and periodic wrap; the footprint's a-scaled derivatives are
// passed as they are.
#pragma once

#include <memory>
#include <string>

#include "absl/status/statusor.h"
#include "base/image.h"
#include "texture/texture_sampler.h"

namespace aperture {

// The lookup options that differ between the peers compared (OIIO::TextureOpt).
struct OiioOptions {
  int anisotropic = 32;   // the most samples along the footprint's long axis
  bool bilinear = false;  // bilinear texels instead of "smart bicubic"
};
// The second OpenImageIO peer of the filter benchmarks, beside its defaults: anisotropic 16,
// bilinear texels (the sharper of its settings at grazing angles).
inline constexpr OiioOptions kOiioAniso16Bilinear = {.anisotropic = 16, .bilinear = true};

class OiioSampler final : public TextureSampler {
 public:
  // Writes the mip-mapped copy to `tx_path` (a temporary file when empty; removed again when the
  // sampler is destroyed) and opens it in a private TextureSystem.
  static absl::StatusOr<std::unique_ptr<OiioSampler>> Create(const Image& image,
                                                             std::string tx_path = "",
                                                             const OiioOptions& options = {});
  ~OiioSampler() override;
  Rgba Sample(const TextureFootprint& f) const override;

 private:
  struct State;
  explicit OiioSampler(std::unique_ptr<State> state);
  std::unique_ptr<State> state_;
};

}  // namespace aperture
