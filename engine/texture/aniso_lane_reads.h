// The texel reads of eight aniso samples at once: the magnified taps, the base probes, the box
// probes, then the table copies of each reading (seed 000, eq. 6-9 inside each copy), one sample
// per vector lane. One kernel (texture/aniso/reads_kernel.inc) compiled for the baseline and for
// AVX2 (texels fetched by gathers) and chosen at run time; both give the same sums bit for bit
// (tests/texture/aniso_sampler_test.cc compares them).
#pragma once

#include <cstdint>
#include <vector>

#include "base/image.h"
#include "texture/aniso_selection.h"
#include "texture/prefiltered_table.h"

namespace aperture {

class LaneReader {
 public:
  // A table that PrefilteredTable::View accepted; it must outlive the reader.
  explicit LaneReader(const PrefilteredTable& table);

  // out[0, n) for lanes [0, n) of a selection (n <= 8) at texture coordinates u, v (repeats),
  // by the AVX2 kernel when the processor has it.
  void Read(const SelectionLanes& s, const double* u, const double* v, int n, Rgba* out) const;
  // The same by the portable kernel alone (what the AVX2 one must equal).
  void ReadPortable(const SelectionLanes& s, const double* u, const double* v, int n,
                    Rgba* out) const;

  // A copy's fields as the skewed bilinear read takes them: broadcast when eight samples read one copy, else
  // `offset` and `shape` gathered (eight 32-bit words a record) and the rest decoded from
  // `shape`.
  struct Copy {
    float width, height, lambda;  // lambda 0 when untilted
    int32_t log2_width, width_mask, height_mask;
    int32_t offset;  // its first texel, counted from the base's
    // log2 width in bits 0-3, log2 height 4-7, tilted to V 8, log2 lambda 9-13, lambda > 0 14.
    int32_t shape;
  };
  static_assert(sizeof(Copy) == 8 * sizeof(int32_t));

 private:
  const uint8_t* texels_ = nullptr;  // the base copy's first texel
  float inv_size_ = 0;               // 1 / 2^n: one base texel in repeats
  int32_t box_copy_ = 0;             // the first copy's directory index (the box probes')
  std::vector<Copy> copies_;         // per directory entry
  bool avx2_ = false;                // Read runs the AVX2 kernel
};

}  // namespace aperture
