#include "texture/aniso_selection.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>

#include "texture/aniso/lanes8.h"

namespace aperture {

// The table's cells as the kernel reads them (CopySelector's members), and the options.
struct CellTable {
  const AnisoOptions& options;
  int log2_size;
  uint32_t first_copy;    // cell (0, 0)'s copy, the 2 x 2 box
  const uint32_t* first;  // per cell j * n + i: its first directory index
  const int32_t* tilts;   // per cell: TiltsPerAxis, 0 for the one untilted copy
  const int32_t* ends;    // per cell: 1 where its end tilts are read
};

namespace {

// Derivatives are clamped to this many texels: a footprint past 2^(3n) (n <= 13) is capped by
// the table anyway, and the squares stay finite in float.
constexpr float kMaxTexels = 0x1p40f;
// Below this second moment (texels^2) the footprint is a point: the base, bilinear.
constexpr float kMinMoment = 1e-30f;
// Probes are this many texels apart along the long side once more than two are needed (1.125
// read 0.4-0.6 dB worse on the asphalt photo at pitch 5, a = 1, and saved 2-4 % of a frame).
constexpr float kProbeSpacing = 1.0f;
// The box probes' spacing: the first copy's box is 2 texels wide.
constexpr float kBoxProbeSpacing = 2.0f;

// 2^e for -126 <= e <= 127.
inline float PowerOfTwo(int e) {
  return std::bit_cast<float>(static_cast<uint32_t>(127 + e) << 23);
}

// For J = 2..9 (index J - 2): SpreadEvenlyLanes' A = ((2J - 2)^2 - 1) / 12, J - 1, J (2J - 1)
// and 0.5 / J.
struct ProbeTable {
  alignas(32) float A[8], J1[8], denominator[8], top[8];
};
constexpr ProbeTable MakeProbeTable() {
  ProbeTable t{};
  for (int i = 0; i < 8; ++i) {
    const float Jf = static_cast<float>(i + 2);
    t.A[i] = (4.0f * (Jf - 1.0f) * (Jf - 1.0f) - 1.0f) * (1.0f / 12.0f);
    t.J1[i] = Jf - 1.0f;
    t.denominator[i] = Jf * (2.0f * Jf - 1.0f);
    t.top[i] = 0.5f / Jf;
  }
  return t;
}
constexpr ProbeTable kProbeTable = MakeProbeTable();
static_assert(SelectionLanes::kMaxProbes / 2 - 2 < 8, "J - 2 indexes eight entries");
static_assert(SelectionLanes::kLanes == lanes8::kLanes);
static_assert(SelectionLanes::kMaxProbes >= 2 * static_cast<int>(2 * 4.0f / kProbeSpacing + 1),
              "the probe lists hold the probes of AnisoOptions::probe_half_extent <= 4");

namespace portable_kernel {
using namespace lanes8::portable;
#include "texture/aniso/selection_kernel.inc"
}  // namespace portable_kernel

#if defined(APERTURE_LANES8_AVX2)
APERTURE_LANES8_AVX2_BEGIN
namespace avx2_kernel {
using namespace lanes8::avx2;
#include "texture/aniso/selection_kernel.inc"
}  // namespace avx2_kernel
APERTURE_LANES8_AVX2_END
#endif

// Lanes [0, n) of d, the rest zero (degenerate: not read).
struct PaddedLanes {
  alignas(32) float d[4][lanes8::kLanes] = {};
  PaddedLanes(const float* dudx, const float* dvdx, const float* dudy, const float* dvdy, int n) {
    const float* in[4] = {dudx, dvdx, dudy, dvdy};
    for (int c = 0; c < 4; ++c) std::copy(in[c], in[c] + n, d[c]);
  }
};

}  // namespace

CopySelector::CopySelector(const PrefilteredTable& table, const AnisoOptions& options)
    : options_(options),
      log2_size_(table.log2_size()),
      half_size_(0.5f * static_cast<float>(table.size())),
      first_copy_(table.cell(0, 0).first),
      kernel_(lanes8::HasAvx2()) {
  const int n = log2_size_;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i < n; ++i) {
      first_.push_back(table.cell(j, i).first);
      tilts_.push_back(static_cast<int32_t>(table.cell(j, i).copies / 2));
      // Beyond a period (H = 2^(i + j) >= 2^n, lambda frozen) a cell's tilts lie far apart for
      // its apertures, and a footprint between two reads copies sheared by up to hundreds of
      // texels. The paper's tilts wrap many times around the texture and average it, as such a
      // footprint does; an end tilt's copy is a line along the texture's diagonal that wraps onto
      // itself and keeps that diagonal's pattern, which a footprint merely near the diagonal
      // does not have (docs/ANISO.md).
      ends_.push_back(i + j < n || options.end_tilts_beyond_period ? 1 : 0);
    }
}

CellTable CopySelector::Cells() const {
  return {options_, log2_size_, first_copy_, first_.data(), tilts_.data(), ends_.data()};
}

void CopySelector::Select(const float* dudx, const float* dvdx, const float* dudy,
                          const float* dvdy, int n, SelectionLanes& out) const {
  if (n < SelectionLanes::kLanes) {
    const PaddedLanes p(dudx, dvdx, dudy, dvdy, n);
    Select(p.d[0], p.d[1], p.d[2], p.d[3], SelectionLanes::kLanes, out);
    return;
  }
  const CellTable cells = Cells();
#if defined(APERTURE_LANES8_AVX2)
  if (kernel_) {
    avx2_kernel::SelectLanes(dudx, dvdx, dudy, dvdy, half_size_, cells, out);
    return;
  }
#endif
  portable_kernel::SelectLanes(dudx, dvdx, dudy, dvdy, half_size_, cells, out);
}

void CopySelector::SelectPortable(const float* dudx, const float* dvdx, const float* dudy,
                                  const float* dvdy, int n, SelectionLanes& out) const {
  const PaddedLanes p(dudx, dvdx, dudy, dvdy, n);
  const CellTable cells = Cells();
  portable_kernel::SelectLanes(p.d[0], p.d[1], p.d[2], p.d[3], half_size_, cells, out);
}

void CopySelector::ShapeSlots(float H, float L, float tg, bool along_v, bool probes,
                              SelectionLanes& out) const {
  using namespace lanes8::portable;
  // Lane 0 reads the shape; lanes 1-7 read nothing.
  alignas(32) float h[8] = {1, 1, 1, 1, 1, 1, 1, 1}, l[8] = {1, 1, 1, 1, 1, 1, 1, 1};
  alignas(32) float t[8] = {}, lane0[8] = {1};
  h[0] = H, l[0] = L, t[0] = tg;
  std::fill(std::begin(out.probe_scale[0]), std::end(out.probe_scale[0]), 1.0f);
  const CellTable cells = Cells();
  portable_kernel::ReadingSlotsLanes(cells, 0, Load(lane0) > Set(0.0f), Load(h), Load(l), Load(t),
                                     SetI(along_v ? 1 : 0), probes, out);
}

// The one-footprint forms (tests, tools): lane 0 of the portable kernel.

ApertureReadings ReadingsOfFootprint(const TextureFootprint& f, int texture_size) {
  using namespace lanes8::portable;
  const PaddedLanes p(&f.dudx, &f.dvdx, &f.dudy, &f.dvdy, 1);
  const portable_kernel::Moments m = portable_kernel::MomentsOfLanes(
      p.d[0], p.d[1], p.d[2], p.d[3], 0.5f * static_cast<float>(texture_size),
      AnisoOptions{}.axis_blend_zone);
  ApertureReadings out;
  if (m.valid.v[0] == 0) return out;
  out.weight[0] = m.first.v[0];
  out.weight[1] = m.second.v[0];
  out.count = out.weight[0] < 1.0f ? 2 : 1;
  for (int k = 0; k < out.count; ++k) {
    const float H = std::sqrt(m.major[k].v[0]), inv_h = 1.0f / H;
    out.shape[k].axis = m.along_v[k].v[0] != 0 ? TiltAxis::kV : TiltAxis::kU;
    out.shape[k].H = H;
    out.shape[k].L = m.area.v[0] * inv_h;
    out.shape[k].tg = m.uv.v[0] * inv_h * inv_h;
  }
  return out;
}

ApertureShape ApertureFromFootprint(const TextureFootprint& f, int texture_size) {
  const ApertureReadings r = ReadingsOfFootprint(f, texture_size);
  return r.count > 0 ? r.shape[0] : ApertureShape{};
}

namespace {

CopyBlend BlendOf(const PrefilteredTable& table, const ApertureShape& shape, bool probes) {
  CopyBlend blend;
  if (shape.axis == TiltAxis::kNone || !(shape.H > 0.0)) {
    blend.magnify = true;  // degenerate derivatives: the base, bilinear
    return blend;
  }
  SelectionLanes lanes{};
  CopySelector(table).ShapeSlots(static_cast<float>(shape.H), static_cast<float>(shape.L),
                                 static_cast<float>(shape.tg), shape.axis == TiltAxis::kV, probes,
                                 lanes);
  for (int s = 0; s < SelectionLanes::kSlots; ++s) {
    if (!(lanes.weight[0][s][0] > 0.0f)) continue;
    blend.copy[blend.count] = lanes.copy[0][s][0];
    blend.weight[blend.count++] = lanes.weight[0][s][0];
  }
  blend.probes = lanes.probes[0][0];
  if (blend.probes > 0) {
    blend.probe_step = lanes.probe_step[0][0];
    blend.probe_weight = lanes.probe_weight[0][0];
    blend.probe_end_weight = lanes.probe_end_weight[0][0];
  }
  blend.box_probes = lanes.box_probes[0][0];
  if (blend.box_probes > 0) {
    blend.box_probe_step = lanes.box_probe_step[0][0];
    blend.box_probe_weight = lanes.box_probe_weight[0][0];
    blend.box_probe_end_weight = lanes.box_probe_end_weight[0][0];
    blend.box_probe_rows = lanes.box_probe_rows[0][0];
  }
  return blend;
}

}  // namespace

CopyBlend SelectCopies(const PrefilteredTable& table, const ApertureShape& shape) {
  return BlendOf(table, shape, true);
}

CopyBlend SelectTableCopies(const PrefilteredTable& table, const ApertureShape& shape) {
  return BlendOf(table, shape, false);
}

}  // namespace aperture
