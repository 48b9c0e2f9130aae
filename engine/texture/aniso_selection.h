// seed 000's copy selection: from a footprint's derivatives to the table copies a sample reads
// and their weights (the aperture parallelogram, eq. 2-4, and the three-point interpolation,
// eq. 5), continuous in the footprint. Eight samples at a time as lanes, by one kernel
// (texture/aniso/selection_kernel.inc, where the formulas are) compiled for the baseline and for
// AVX2 and chosen at run time; both give the same floats (tests/texture/aniso_selection_test.cc
// checks it bit for bit).
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

#include "texture/aniso/aniso_options.h"
#include "texture/prefiltered_table.h"
#include "texture/texture_sampler.h"

namespace aperture {

// The aperture parallelogram in texel units: half-extent H along the major axis (the tilt axis),
// half-thickness L along the minor one, tg the slope of the long side to the major axis.
struct ApertureShape {
  TiltAxis axis = TiltAxis::kNone;  // kNone: degenerate (all derivatives zero or not finite)
  double H = 0, L = 0, tg = 0;
};

// The readings a sample blends. A footprint has a parallelogram of its second moments along
// either texture axis (see MomentsOfLanes in the kernel); the first reading is along the axis
// of the larger moment. Where the two moments are nearly equal (the footprint's long side near a
// diagonal) that choice would jump, so both are read, their weights going linearly from one to
// the other across a zone (AnisoOptions::axis_blend_zone).
struct ApertureReadings {
  int count = 0;  // 0: degenerate derivatives
  ApertureShape shape[2];
  float weight[2] = {};
};
ApertureReadings ReadingsOfFootprint(const TextureFootprint& f, int texture_size);

// The first reading: seed 000, eq. 2-4 read as the parallelogram with the pixel's second
// moments (rotation-invariant), along the axis of the larger moment.
ApertureShape ApertureFromFootprint(const TextureFootprint& f, int texture_size);

// The extents of the copies read for an aperture of half-extent x texels (H or L; a deviation
// from seed 000, eq. 5, which reads the copies of extent x). A copy of half-extent c is read by
// a bilinear interpolation between its texels, which are c apart, so along that axis its
// kernel is the box of half-width c convolved with a tent of half-width c. The pixel's box on
// the bilinear base is the box of half-width x convolved with a tent of one texel. At
// c = x = 1 these are the same kernel; for longer apertures the copy's tent outgrows the
// base's, and c = x blurs: the copy's variance is x^2 / 2 against x^2 / 3 + 1 / 6. For a long
// aperture (the base's tent negligible) the copy nearest the box in L2, in one dimension, has
// c = 0.90 x on white noise and c = 0.85-0.86 x on an edge (a step's spectrum). Its L2
// distances to the box are 0.0430 and 0.00134, against 0.0500 and 0.00397 at c = x and 0.0472
// and 0.00163 at the variance-matched c = 0.816 x (x = 1, the box of height 1/2;
// scripts/copy-kernel-l2.py). The extent c^2 = 0.8 x^2 + 0.2 is 1 at x = 1 (continuous with
// the magnification blend below it), 0.92 x at x = 2 and tends to 0.89 x: between the two
// optima. aperture-bench filter scores it +1.4 dB on the checkerboard at pitches 3-20, the
// photos within 0.1 dB. Below x = 1 (magnification, or the thin side,
// which the base probes filter) the extent is x.
inline constexpr float kCopyExtentScale = AnisoOptions{}.copy_extent_scale;
inline float CopyExtent(float x) {
  return x < 1.0f ? x : std::sqrt(kCopyExtentScale * x * x + (1.0f - kCopyExtentScale));
}

// The copies one reading reads and their weights: seed 000, eq. 5 across cells, and between the
// two tilts of a cell nearest the reading's tangent (a continuous extension: the paper takes the
// nearest tilt and leaves the rest to the skewed read, eq. 6-9, which jumps where the nearest
// changes; docs/ENGINE.md). The tilts include the ends tg = +-1 (TiltsPerAxis).
struct CopyBlend {
  static constexpr int kMaxCopies = 6;  // three cells, two tilts each
  bool magnify = false;                 // degenerate derivatives: bilinear on the unfiltered base
  int count = 0;                        // entries below count, every weight above 0
  uint32_t copy[kMaxCopies] = {};       // directory indices
  float weight[kMaxCopies] = {};
  // L < 1, thinner than the table's thinnest copy: also `probes` bilinear reads of the base
  // along the long side, `probe_step` texels apart along the major axis and centred on the
  // sample; the outer two weigh `probe_end_weight`, the others `probe_weight`.
  int probes = 0;
  float probe_step = 0, probe_weight = 0, probe_end_weight = 0;
  // 1 <= H < 8 and L < 1.375: also `box_probes` bilinear reads of the first copy
  // (the 2 x 2 box) along the long side, `box_probe_step` texels apart, in two rows
  // +-box_probe_rows texels across (one row when that is 0), each read of a pair weighing half
  // (AddBoxProbesLanes in the kernel).
  int box_probes = 0;
  float box_probe_step = 0, box_probe_weight = 0, box_probe_end_weight = 0, box_probe_rows = 0;
};
// seed 000, eq. 5, below L = 1 the base probes (a deviation: the paper's table ends at L = 1,
// which filters a thinner footprint's short side up to twice too wide) and below L = 1.375 the
// box probes: one
// reading's blend. The sampler reads a footprint whose long half-axis is under a texel by the
// magnified taps (SelectionLanes::taps_share, from the footprint, not from a reading), fading
// into the readings' blend between 0.875 and 1 texel.
CopyBlend SelectCopies(const PrefilteredTable& table, const ApertureShape& shape);
// The paper's selection alone (with the tilt blend), without the base and box probes.
CopyBlend SelectTableCopies(const PrefilteredTable& table, const ApertureShape& shape);

// The selections of up to eight samples, lane by lane. Per lane two readings; per reading six
// slots (three cells of eq. 5, two tilts each) whose zero weights are not read, the base probes
// and the box probes.
struct SelectionLanes {
  static constexpr int kLanes = 8;
  static constexpr int kSlots = CopyBlend::kMaxCopies;
  alignas(32) float reading_weight[2][kLanes];  // 0: not read (both 0: degenerate derivatives)
  alignas(32) float H[2][kLanes];
  alignas(32) float L[2][kLanes];
  alignas(32) float tg[2][kLanes];
  alignas(32) int32_t along_v[2][kLanes];  // 1: the reading's major axis is V
  alignas(32) uint32_t copy[2][kSlots][kLanes];
  alignas(32) float weight[2][kSlots][kLanes];
  // At most this many base probes a reading (H < 8 texels, a texel apart).
  static constexpr int kMaxProbes = 18;
  alignas(32) int32_t probes[2][kLanes];  // the base probes: count, spacing (texels) and weights
  float probe_step[2][kLanes];
  float probe_weight[2][kLanes];
  float probe_end_weight[2][kLanes];
  // The probes' positions are scaled by this (1 but for magnified readings, whose probes lie
  // along the footprint's principal axis: see MagnifiedInPrincipalAxesLanes in the kernel).
  alignas(32) float probe_scale[2][kLanes];
  // The box probes (CopyBlend::box_probes): count, spacing, weights and the rows' offset across,
  // in texels (0: one row).
  alignas(32) int32_t box_probes[2][kLanes];
  float box_probe_step[2][kLanes];
  float box_probe_weight[2][kLanes];
  float box_probe_end_weight[2][kLanes];
  float box_probe_rows[2][kLanes];
  // The magnified taps (MagnifiedTapsLanes in the kernel), per lane, not per reading: their share w
  // of the sample (the readings' weights are scaled by 1 - w; 0: none), the first copy's weight
  // (read at the sample), each of the four base reads' weight, and the reads' offsets +-p and
  // +-q in texels (u, v).
  alignas(32) float taps_share[kLanes];
  alignas(32) float taps_first[kLanes];
  alignas(32) float taps_weight[kLanes];
  alignas(32) float tap_p[2][kLanes];
  alignas(32) float tap_q[2][kLanes];
};

struct CellTable;  // the kernels' view of a CopySelector's cells (aniso_selection.cc)

class CopySelector {
 public:
  explicit CopySelector(const PrefilteredTable& table, const AnisoOptions& options = {});

  // Lanes [0, n) of `out` (n <= 8) for the footprints with these derivatives, by the AVX2
  // kernel when the processor has it; the base probes included.
  void Select(const float* dudx, const float* dvdx, const float* dudy, const float* dvdy, int n,
              SelectionLanes& out) const;
  // The same by the portable kernel alone (what the AVX2 one must equal).
  void SelectPortable(const float* dudx, const float* dvdx, const float* dudy, const float* dvdy,
                      int n, SelectionLanes& out) const;
  bool has_kernel() const { return kernel_; }

  // Reading 0 of lane 0 for this shape as it is (no principal axes), by the portable kernel:
  // seed 000, eq. 5 with the tilt blend, and the base and box probes when `probes`.
  void ShapeSlots(float H, float L, float tg, bool along_v, bool probes, SelectionLanes& out) const;

 private:
  CellTable Cells() const;

  AnisoOptions options_;
  int log2_size_ = 0;
  float half_size_ = 0;  // 2^n / 2: one step of the paper's 2 x 2 aperture, in texels per repeat
  uint32_t first_copy_ = 0;      // cell (0, 0)'s copy, the 2 x 2 box
  std::vector<uint32_t> first_;  // per cell j * n + i: its first directory index
  std::vector<int32_t> tilts_;   // per cell: TiltsPerAxis, 0 for the one untilted copy
  std::vector<int32_t> ends_;    // per cell: 1 where its end tilts are read
  bool kernel_ = false;
};

}  // namespace aperture
