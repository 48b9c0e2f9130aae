// Seed 003, eq. 3-4: the colour of a pixel's projection abcd on the texture plane, the integral of
// the texture over its fragments divided by their area, with the integrals of the child
// fragments taken from a summed-area table (raster textures) or the packed format's exact area
// integral (seed 001's vector textures, without unpacking).
#pragma once

#include <array>
#include <vector>

#include "base/image.h"
#include "texture/summed_area_table.h"
#include "trace/pixel_fragments.h"
#include "trace/texture_integral.h"

namespace aperture {

// Totals over the quads integrated, for the measured mean S_fragments / S_quad - 1.
struct FragmentStats {
  double quads = 0;               // integrated by fragments
  double relative_error_sum = 0;  // sum of S_fragments / S_quad - 1 over them
  double fragments = 0, children = 0;
  double exact = 0, exact_steps = 0;  // quads integrated exactly, and their steps
  // Of those, on a coarser mip level where the fragments' work cap breaks eq. 9's bound, and the
  // sum of their levels (the texture's size in levels for its mean).
  double coarse = 0, coarse_level_sum = 0;

  // The mean of S_fragments / S_quad - 1 over the quads integrated exactly (counting 0: they
  // have no cover) or by fragments, not those on a coarser level; and over the fragments' only.
  double MeanRelativeError() const {
    const double n = quads + exact - coarse;
    return n > 0 ? relative_error_sum / n : 0;
  }
  double FragmentMeanRelativeError() const { return quads > 0 ? relative_error_sum / quads : 0; }
  double ExactShare() const { return Share(exact); }
  double Share(double count) const { return exact + quads > 0 ? count / (exact + quads) : 0; }
  void Add(const FragmentStats& o) {
    quads += o.quads, relative_error_sum += o.relative_error_sum;
    fragments += o.fragments, children += o.children;
    exact += o.exact, exact_steps += o.exact_steps;
    coarse += o.coarse;
    coarse_level_sum += o.coarse_level_sum;
  }
};

// Keeps its scratch buffers between calls: one per thread.
class ProjectionIntegrator {
 public:
  explicit ProjectionIntegrator(FragmentOptions options) : options_(options) {}

  // The mean of the texture over `quad` (texture repeats): exactly, by its edges against the
  // summed-area table, where that is cheap enough (FragmentOptions::exact_steps); else over the
  // fragments covering it, raster textures by their summed-area table, packed vector textures by
  // their own area integral.
  Rgba Color(const std::array<TexPoint, 4>& quad, const TextureIntegral& texture,
             FragmentStats* stats = nullptr);
  Rgba Color(const std::array<TexPoint, 4>& quad, const SummedAreaTable& sat,
             FragmentStats* stats = nullptr) {
    return Color(quad, TableIntegral(sat), stats);
  }

 private:
  // The exact mean of the base level; false for the fragments, with the base level's steps in
  // `base_steps` (0 when its shape was refused).
  bool ExactMean(const std::array<TexPoint, 4>& q, const TextureIntegral& sat,
                 std::array<double, 4>* mean, int* base_steps, FragmentStats* stats) const;
  // The exact mean of the finest coarser mip level within the step budget, or the texture's mean
  // when none is.
  void CoarseMean(const std::array<TexPoint, 4>& q, const TextureIntegral& sat, int base_steps,
                  std::array<double, 4>* mean, FragmentStats* stats) const;

  FragmentOptions options_;
  FragmentSet set_;
  std::vector<TexRect> children_;
};

}  // namespace aperture
