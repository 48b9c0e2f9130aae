// seed 000's lookup in a prefiltered table: the copies a footprint selects (texture/
// aniso_selection: the aperture parallelogram, eq. 2-4, and the three-point interpolation,
// eq. 5), read by a skewed bilinear interpolation inside each copy (eq. 6-9). Periodic wrap.
#pragma once

#include "texture/aniso_lane_reads.h"
#include "texture/aniso_selection.h"
#include "texture/prefiltered_table.h"
#include "texture/texture_sampler.h"

namespace aperture {

class AnisoSampler final : public TextureSampler {
 public:
  // The table must outlive the sampler; the options are valid (AnisoOptions::Validate).
  explicit AnisoSampler(PrefilteredTable table, const AnisoOptions& options = {});
  Rgba Sample(const TextureFootprint& f) const override;
  // The same results as Sample, in two phases over groups of samples (the apertures and copy
  // selections of the group, then its texel reads), so that independent samples overlap in the
  // processor instead of waiting one after the other on their chains of dependent loads.
  void SampleMany(const TextureFootprint* in, Rgba* out, int count) const override;
  // The same over the renderer's batches (no copy into footprint structs first).
  void SampleBatch(const FootprintBatch& in, Rgba* out) const override;

  // seed 000, eq. 6-9: skewed bilinear inside one copy along slope `tg` (plain bilinear for
  // untilted copies); u, v in repeats.
  Rgba SampleCopy(const CopyEntry& e, double u, double v, double tg) const;

 private:
  // Up to eight samples from derivative and coordinate arrays: their selection, then their reads.
  void SampleLanes(const float* dudx, const float* dvdx, const float* dudy, const float* dvdy,
                   const double* u, const double* v, int n, Rgba* out) const;

  PrefilteredTable table_;
  CopySelector selector_;
  LaneReader reader_;
};

}  // namespace aperture
