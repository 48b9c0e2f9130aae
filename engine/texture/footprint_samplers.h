// The samplers of a scene texture that need more than its mip-map: seed 000's table (aniso),
// OpenImageIO's TextureSystem (oiio) and the supersampled reference. Each is built on its first
// use, once, so scenes that never ask for them pay nothing. With a shared store the table is
// taken from it (built there once for every process on the machine) and used in place.
#pragma once

#include <atomic>
#include <functional>
#include <memory>
#include <mutex>

#include "absl/status/status.h"
#include "base/image.h"
#include "store/shared_store.h"
#include "texture/prefiltered_table.h"
#include "texture/texture_sampler.h"

namespace aperture {

class FootprintSamplers {
 public:
  // `base`: the power-of-two texture (the pyramid's level 0); must outlive this object.
  FootprintSamplers(const Image& base, std::shared_ptr<const SharedStore> store)
      : base_(base), store_(std::move(store)) {}
  ~FootprintSamplers();

  // Builds (or attaches) the aniso table now; the error when that fails. `stop` can stop a
  // build part-way (Cancelled; a later call builds again).
  absl::Status PrepareAniso(const std::function<bool()>& stop = nullptr) const;

  // The sampler for kAniso, kOiio or kReference; `fallback` (trilinear) when building the
  // table or the OpenImageIO copy fails (logged) or for any other mode.
  const TextureSampler& Get(FilterMode mode, const TextureSampler& fallback) const;

 private:
  const Image& base_;
  std::shared_ptr<const SharedStore> store_;
  mutable std::once_flag oiio_once_, reference_once_;
  mutable std::mutex aniso_mutex_;
  mutable std::atomic<bool> aniso_done_{false};
  mutable absl::Status aniso_status_;
  mutable std::shared_ptr<const void> table_bytes_;  // a StoreEntry or a TableBlock
  mutable std::unique_ptr<TextureSampler> aniso_, oiio_, reference_;
};

}  // namespace aperture
