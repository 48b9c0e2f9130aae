#include "texture/aniso_lane_reads.h"

#include <algorithm>
#include <bit>

#include "texture/aniso/lanes8.h"

namespace aperture {
namespace {

namespace portable_kernel {
using namespace lanes8::portable;
#include "texture/aniso/reads_kernel.inc"
}  // namespace portable_kernel

#if defined(APERTURE_LANES8_AVX2)
APERTURE_LANES8_AVX2_BEGIN
namespace avx2_kernel {
using namespace lanes8::avx2;
#include "texture/aniso/reads_kernel.inc"
}  // namespace avx2_kernel
APERTURE_LANES8_AVX2_END
#endif

}  // namespace

LaneReader::LaneReader(const PrefilteredTable& table)
    : texels_(table.texels(table.base())),
      inv_size_(1.0f / static_cast<float>(table.size())),
      box_copy_(static_cast<int32_t>(table.cell(0, 0).first)),
      avx2_(lanes8::HasAvx2()) {
  // PrefilteredTable::View checked that every copy lies at a 32-bit texel index of the base's;
  // the builder makes every extent and lambda a power of two up to 2^13.
  const uint64_t base = table.base().offset;
  for (const CopyEntry& e : table.directory()) {
    int32_t shape = std::countr_zero(e.width) | std::countr_zero(e.height) << 4;
    if (e.axis == TiltAxis::kV) shape |= portable_kernel::kTiltV;
    if (e.axis != TiltAxis::kNone)
      shape |= std::countr_zero(e.lambda) << 9 | portable_kernel::kTilted;
    copies_.push_back({static_cast<float>(e.width), static_cast<float>(e.height),
                       e.axis == TiltAxis::kNone ? 0.0f : static_cast<float>(e.lambda),
                       std::countr_zero(e.width), static_cast<int32_t>(e.width - 1),
                       static_cast<int32_t>(e.height - 1),
                       static_cast<int32_t>((e.offset - base) / 4), shape});
  }
}

void LaneReader::Read(const SelectionLanes& s, const double* u, const double* v, int n,
                      Rgba* out) const {
#if defined(APERTURE_LANES8_AVX2)
  if (avx2_) {
    avx2_kernel::ReadLanes({texels_, copies_.data(), box_copy_}, inv_size_, s, u, v, n, out);
    return;
  }
#endif
  ReadPortable(s, u, v, n, out);
}

void LaneReader::ReadPortable(const SelectionLanes& s, const double* u, const double* v, int n,
                              Rgba* out) const {
  portable_kernel::ReadLanes({texels_, copies_.data(), box_copy_}, inv_size_, s, u, v, n, out);
}

}  // namespace aperture
