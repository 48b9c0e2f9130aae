// The seed 000 sampler's tuned constants and its regimes' switches, with their defaults
// (docs/ANISO.md has the figure behind each). Trying another value is a flag, not a rebuild:
// `aperture-bench filter --aniso-options NAME=VALUE,...`.
#pragma once

#include <string>

#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"

namespace aperture {

struct AnisoOptions {
  // Two readings, along U and along V, where the footprint's long axis is near a diagonal:
  // |M_uu - M_vv| < zone D, D = sqrt((M_uu - M_vv)^2 + 4 M_uv^2), i.e. |cos 2 phi| < zone
  // (0.125: within 3.6 degrees of a diagonal). 0: one reading always.
  float axis_blend_zone = 0.125f;
  // The copies read for an aperture of half-extent x >= 1 texel have c^2 = s x^2 + (1 - s)
  // (CopyExtent in aniso_selection.h). 1: the paper's c = x.
  float copy_extent_scale = 0.8f;
  // The base and box probes carry apertures up to this half-extent H (texels), fading out up to
  // twice it. At most 4: the probe lists hold 18 reads.
  float probe_half_extent = 4.0f;
  // The box probes read apertures thinner than this half-thickness L (texels), whole up to
  // box_probe_thickness - 1 / box_probe_fade and fading into the table's copies above it.
  float box_probe_thickness = 1.375f;
  float box_probe_fade = 8.0f;
  // The magnified taps take a footprint whose long half-axis is under 1 - 1 / taps_fade texel,
  // fading into the readings' blend up to 1 texel.
  float taps_fade = 8.0f;
  // The regimes that go beyond the paper (docs/ANISO.md); false: that regime is not read.
  bool magnified_taps = true;
  bool principal_axes = true;
  bool base_probes = true;
  bool box_probes = true;
  // The end tilts tg = +-1 read beyond a period too (the cells of H >= 2^n, where lambda is
  // frozen); false: only the paper's tilts there.
  bool end_tilts_beyond_period = false;

  // An error naming the first field out of its range.
  absl::Status Validate() const;
  // "name=value,name=value" (names as above; true/false for the switches) over the defaults;
  // an error names an unknown name or a bad value. Empty: the defaults.
  static absl::StatusOr<AnisoOptions> Parse(absl::string_view text);
  // The fields that differ from the defaults, in Parse's form ("" for the defaults).
  std::string ChangedFields() const;
};

}  // namespace aperture
