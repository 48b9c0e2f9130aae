// seed 000's lookup in a prefiltered table: the aperture parallelogram from the derivatives
// (eq. 2-4), three neighbouring copies blended by the three-point interpolation (eq. 5), and a
// skewed bilinear interpolation inside each copy (eq. 6-9). Periodic wrap.
#pragma once

#include <cstdint>
#include <vector>

#include "texture/prefiltered_table.h"
#include "texture/texture_sampler.h"

namespace aperture {

// The aperture parallelogram in texel units: half-extent H along the major axis (the tilt axis),
// half-thickness L along the minor one, tg the slope of the long side to the major axis.
struct ApertureShape {
  TiltAxis axis = TiltAxis::kNone;  // kNone: degenerate (all derivatives zero or not finite)
  double H = 0, L = 0, tg = 0;
};

// The table copy for a footprint whose derivatives are in repeats per pixel times the aperture a
// (the paper's 2 x 2 aperture is a = 2, derivatives of one pixel step): seed 000, eq. 2-4 read as
// the parallelogram with the pixel's second moments (rotation-invariant; see the definition),
// along the texture axis of the larger moment.
ApertureShape ApertureFromFootprint(const TextureFootprint& f, int texture_size);

// The readings a sample blends (issue 22, part 3: continuity). A footprint has a parallelogram of
// its second moments along either texture axis; ApertureFromFootprint takes the axis of the
// larger moment. Where the two moments are nearly equal (the footprint's long side near a
// diagonal) the choice would jump, so both readings are blended, their weights going linearly
// from one to the other across the zone |M_uu - M_vv| < kAxisBlendZone (M_uu + M_vv).
inline constexpr double kAxisBlendZone = 0.125;
struct ApertureReadings {
  int count = 0;  // 0: degenerate derivatives
  ApertureShape shape[2];
  float weight[2] = {};
};
ApertureReadings ReadingsOfFootprint(const TextureFootprint& f, int texture_size);

// The copies one reading reads and their weights: seed 000, eq. 5 across cells, and between the
// two tilts of a cell nearest the reading's tangent (a continuous extension: the paper takes the
// nearest tilt and leaves the rest to the skewed read, eq. 6-9, which jumps where the nearest
// changes; docs/ENGINE.md).
struct CopyBlend {
  static constexpr int kMaxCopies = 6;  // three cells, two tilts each
  bool magnify = false;       // degenerate derivatives: bilinear on the unfiltered base copy
  int count = 0;              // the entries below count are set, and every weight is above 0
  uint32_t copy[kMaxCopies];  // directory indices
  float weight[kMaxCopies];
  // L < 1, thinner than the table's thinnest copy: also `probes` bilinear reads of the base
  // along the long side, `probe_step` texels apart along the major axis and centred on the
  // sample; the outer two weigh `probe_end_weight`, the others `probe_weight` (see
  // AddBaseProbes).
  int probes = 0;
  float probe_step = 0, probe_weight = 0, probe_end_weight = 0;
};
// seed 000, eq. 5, and below L = 1 the base probes (a deviation: the paper's table ends at
// L = 1; docs/BENCHMARKS.md, issue 3, measures it).
CopyBlend SelectCopies(const PrefilteredTable& table, const ApertureShape& shape);
// The paper's selection alone (with the tilt blend), without the base probes for L < 1.
CopyBlend SelectTableCopies(const PrefilteredTable& table, const ApertureShape& shape);

class AnisoSampler final : public TextureSampler {
 public:
  // The table must outlive the sampler.
  explicit AnisoSampler(PrefilteredTable table);
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
  // What the skewed bilinear read of a copy needs, precomputed per copy (directory order): the
  // reads of a sample chain through it, so it is kept small and conversion-free.
  struct CopyLayout {
    const uint8_t* texels;
    float width, height;  // texels along U and V, as floats
    float lambda;         // the cell's lambda; 0 when untilted (no skew)
    uint32_t width_mask, height_mask;
    bool tilt_v;
  };
  CopyLayout LayoutOf(const CopyEntry& e) const;
  // What one sample reads: its readings and each one's copies.
  struct Selection {
    ApertureReadings readings;
    CopyBlend blend[2];
  };
  void Select(const TextureFootprint& f, Selection& out) const;
  // visit(layout, u, v, tg, weight) for each copy read of a sample, in the order they are summed.
  template <typename Visit>
  void ForEachRead(const TextureFootprint& f, const Selection& s, Visit visit) const;
  // A group of samples selected and their copy reads (Blend's, in its order) listed, then the
  // reads' addresses and weights computed eight at a time by an AVX2 kernel; the same floats as
  // Blend.
  void BlendReads(const TextureFootprint* f, int n, Rgba* out) const;
  template <typename FootprintOf>
  void SampleGroups(FootprintOf footprint_of, Rgba* out, int count) const;
  Rgba Blend(const TextureFootprint& f, const Selection& s) const;

  PrefilteredTable table_;
  std::vector<CopyLayout> layouts_;
  bool read_kernel_ = false;  // BlendReads: AVX2 present and every copy under 2^31 texels
};

}  // namespace aperture
