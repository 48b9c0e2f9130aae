// The samplers of a scene texture that need more than its mip-map: seed 000's table (aniso),
// OpenImageIO's TextureSystem (oiio) and the supersampled reference. Each is built on its first
// use, once, so scenes that never ask for them pay nothing. With a shared store the table is
// taken from it (built there once for every process on the machine) and used in place. A filter
// that cannot be built is an error naming it, never another filter in its place: a frame drawn
// with a filter it did not ask for would pass for the one it asked for.
#pragma once

#include <atomic>
#include <functional>
#include <memory>
#include <mutex>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
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

  // The sampler for kAniso, kOiio or kReference, built on the first call. An error naming the
  // filter when it cannot be built (the table cannot be built or read from the store, OpenImageIO
  // refuses the texture; the same error on every later call) or for any other mode, whose
  // samplers the mip-map has. `stop` can stop the table's build part-way, as in PrepareAniso.
  absl::StatusOr<const TextureSampler*> Get(FilterMode mode,
                                            const std::function<bool()>& stop = nullptr) const;

 private:
  const Image& base_;
  std::shared_ptr<const SharedStore> store_;
  mutable std::once_flag oiio_once_, reference_once_;
  mutable absl::Status oiio_status_;
  mutable std::mutex aniso_mutex_;
  mutable std::atomic<bool> aniso_done_{false};
  mutable absl::Status aniso_status_;
  mutable std::shared_ptr<const void> table_bytes_;  // a StoreEntry or a TableBlock
  mutable std::unique_ptr<TextureSampler> aniso_, oiio_, reference_;
};

}  // namespace aperture
