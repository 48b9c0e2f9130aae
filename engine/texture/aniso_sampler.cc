#include "texture/aniso_sampler.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "texture/footprint_batch.h"

#if defined(__SSE4_1__)
#include <smmintrin.h>
#endif

namespace aperture {
namespace {

// Four channels in texel units (0..255) while interpolating; scaled by 1/255 once at the end.
#if defined(__SSE4_1__)
using V4 = __m128;
inline V4 Zero() { return _mm_setzero_ps(); }
inline V4 LoadTexel(const uint8_t* t) {
  int32_t bits;
  std::memcpy(&bits, t, sizeof(bits));
  return _mm_cvtepi32_ps(_mm_cvtepu8_epi32(_mm_cvtsi32_si128(bits)));
}
inline V4 Mix(V4 a, V4 b, float w) {
  return _mm_add_ps(a, _mm_mul_ps(_mm_sub_ps(b, a), _mm_set1_ps(w)));
}
inline V4 AddScaled(V4 acc, V4 a, float w) {
  return _mm_add_ps(acc, _mm_mul_ps(a, _mm_set1_ps(w)));
}
inline Rgba ToRgba(V4 v) {
  float out[4];
  _mm_storeu_ps(out, v);
  return {out[0], out[1], out[2], out[3]};
}
#else
struct V4 {
  float c[4];
};
inline V4 Zero() { return {{0, 0, 0, 0}}; }
inline V4 LoadTexel(const uint8_t* t) {
  return {{float(t[0]), float(t[1]), float(t[2]), float(t[3])}};
}
inline V4 Mix(V4 a, V4 b, float w) {
  for (int i = 0; i < 4; ++i) a.c[i] += (b.c[i] - a.c[i]) * w;
  return a;
}
inline V4 AddScaled(V4 acc, V4 a, float w) {
  for (int i = 0; i < 4; ++i) acc.c[i] += a.c[i] * w;
  return acc;
}
inline Rgba ToRgba(V4 v) { return {v.c[0], v.c[1], v.c[2], v.c[3]}; }
#endif

template <typename Layout>
inline V4 Fetch(const Layout& c, int x, int y) {
  return LoadTexel(c.texels + 4 * (static_cast<size_t>(static_cast<uint32_t>(y) & c.height_mask) *
                                       (c.width_mask + 1) +
                                   (static_cast<uint32_t>(x) & c.width_mask)));
}

// seed 000, eq. 6-9 inside one copy, in texel units (0..255); plain bilinear when untilted.
// Inlined into the blend of three copies so that their texel reads overlap.
template <typename Layout>
[[gnu::always_inline]] inline V4 CopySample(const Layout& c, float u, float v, float tg) {
  // Texel centres at +0.5 (DESIGN.md).
  const float X = u * c.width - 0.5f;
  const float Y = v * c.height - 0.5f;
  // Major coordinate M (along the tilt axis) and minor coordinate m, in copy texels; the shift
  // is lambda tg minor texels per major texel along the long side (0 when untilted).
  const float M = c.tilt_v ? Y : X, m = c.tilt_v ? X : Y;
  const float shift = c.lambda * tg;
  const float M0 = std::floor(M), fM = M - M0;
  // seed 000, eq. 6 (tilt to U) / eq. 7 (tilt to V): the minor coordinate on both neighbouring
  // major lines, moved along the long side.
  const float m1 = m - fM * shift, m2 = m + (1.0f - fM) * shift;
  const float m1f = std::floor(m1), m2f = std::floor(m2);
  const int a = static_cast<int>(M0), b1 = static_cast<int>(m1f), b2 = static_cast<int>(m2f);
  auto at = [&](int major, int minor) {
    return c.tilt_v ? Fetch(c, minor, major) : Fetch(c, major, minor);
  };
  // seed 000, eq. 8 / 9.
  return Mix(Mix(at(a, b1), at(a, b1 + 1), m1 - m1f),
             Mix(at(a + 1, b2), at(a + 1, b2 + 1), m2 - m2f), fM);
}

// The base probes (kBox false) or the box probes (kBox true) of reading r of a lane
// (texture/aniso/selection_kernel.inc: AddProbesLanes, AddBoxProbesLanes): visit(u', v', weight) for each,
// in order, where it is read (a bilinear read of the base or the first copy, both untilted);
// `scale` multiplies every weight. A box probe in two rows is two reads of half its weight, the
// row -d first.
template <bool kBox, typename Visit>
[[gnu::always_inline]] inline void ForEachProbe(const SelectionLanes& s, int r, int lane, float u,
                                                float v, float inv_size, float scale, Visit visit) {
  const int probes = kBox ? s.box_probes[r][lane] : s.probes[r][lane];
  // The other probe fields are only set when there are probes (reading them otherwise could
  // load a stale denormal, which costs a microcode assist a multiplication).
  if (probes == 0) return;
  // Along the major axis, and tg times that along the minor one; in repeats.
  const float step = (kBox ? s.box_probe_step[r][lane] : s.probe_step[r][lane]) * inv_size;
  const float first = -0.5f * static_cast<float>(probes - 1) * step;
  const float tg = s.tg[r][lane];
  const float w = (kBox ? s.box_probe_weight[r][lane] : s.probe_weight[r][lane]) * scale;
  const float w_end =
      (kBox ? s.box_probe_end_weight[r][lane] : s.probe_end_weight[r][lane]) * scale;
  const bool along_u = s.along_v[r][lane] == 0;
  const float d = kBox ? s.box_probe_rows[r][lane] * inv_size : 0.0f;
  for (int k = 0; k < probes; ++k) {
    const float major = first + static_cast<float>(k) * step, minor = major * tg;
    const float wk = k == 0 || k == probes - 1 ? w_end : w;
    if (kBox && d > 0.0f) {
      const float below = minor - d, above = minor + d, half = 0.5f * wk;
      visit(u + (along_u ? major : below), v + (along_u ? below : major), half);
      visit(u + (along_u ? major : above), v + (along_u ? above : major), half);
    } else {
      visit(u + (along_u ? major : minor), v + (along_u ? minor : major), wk);
    }
  }
}

}  // namespace

AnisoSampler::CopyLayout AnisoSampler::LayoutOf(const CopyEntry& e) const {
  return {table_.texels(e),
          static_cast<float>(e.width),
          static_cast<float>(e.height),
          e.axis == TiltAxis::kNone ? 0.0f : static_cast<float>(e.lambda),
          e.width - 1,
          e.height - 1,
          e.axis == TiltAxis::kV};
}

AnisoSampler::AnisoSampler(PrefilteredTable table)
    : table_(std::move(table)), selector_(table_), lane_reader_(LaneReader::For(table_)) {
  layouts_.reserve(table_.directory().size());
  for (const CopyEntry& e : table_.directory()) layouts_.push_back(LayoutOf(e));
}

Rgba AnisoSampler::SampleCopy(const CopyEntry& e, double u, double v, double tg) const {
  const V4 r =
      CopySample(LayoutOf(e), static_cast<float>(u), static_cast<float>(v), static_cast<float>(tg));
  return ToRgba(AddScaled(Zero(), r, 1.0f / 255.0f));
}

template <typename Visit>
void AnisoSampler::ForEachRead(const SelectionLanes& s, int lane, float u, float v,
                               Visit visit) const {
  const bool taps = s.taps_share[lane] > 0.0f;
  if (!taps && !(s.reading_weight[0][lane] > 0.0f) && !(s.reading_weight[1][lane] > 0.0f)) {
    visit(layouts_[0], u, v, 0.0f, 1.0f / 255.0f);  // degenerate derivatives: the base, bilinear
    return;
  }
  const float inv_size = 1.0f / table_.size();
  if (taps) {
    // The magnified taps (texture/aniso/selection_kernel.inc: MagnifiedTapsLanes): the first copy at the
    // sample, then the base at +p, -p, +q, -q.
    visit(layouts_[table_.cell(0, 0).first], u, v, 0.0f, s.taps_first[lane] * (1.0f / 255.0f));
    const float w = s.taps_weight[lane] * (1.0f / 255.0f);
    const float pu = s.tap_p[0][lane] * inv_size, pv = s.tap_p[1][lane] * inv_size;
    const float qu = s.tap_q[0][lane] * inv_size, qv = s.tap_q[1][lane] * inv_size;
    visit(layouts_[0], u + pu, v + pv, 0.0f, w);
    visit(layouts_[0], u - pu, v - pv, 0.0f, w);
    visit(layouts_[0], u + qu, v + qv, 0.0f, w);
    visit(layouts_[0], u - qu, v - qv, 0.0f, w);
  }
  for (int r = 0; r < 2; ++r) {
    if (!(s.reading_weight[r][lane] > 0.0f)) continue;
    const float scale = s.reading_weight[r][lane] / 255.0f;
    ForEachProbe<false>(s, r, lane, u, v, inv_size, scale,
                        [&](float pu, float pv, float w) { visit(layouts_[0], pu, pv, 0.0f, w); });
    const CopyLayout& box = layouts_[table_.cell(0, 0).first];
    ForEachProbe<true>(s, r, lane, u, v, inv_size, scale,
                       [&](float pu, float pv, float w) { visit(box, pu, pv, 0.0f, w); });
    // The sample's own tangent: the skew interpolates between tilts (seed 000, eq. 6-9).
    const float tg = s.tg[r][lane];
    for (int slot = 0; slot < SelectionLanes::kSlots; ++slot) {
      const float w = s.weight[r][slot][lane];
      if (!(w > 0.0f)) continue;
      visit(layouts_[s.copy[r][slot][lane]], u, v, tg, w * scale);
    }
  }
}

Rgba AnisoSampler::Blend(const SelectionLanes& s, int lane, float u, float v) const {
  V4 sum = Zero();
  ForEachRead(s, lane, u, v, [&](const CopyLayout& c, float pu, float pv, float tg, float w) {
    sum = AddScaled(sum, CopySample(c, pu, pv, tg), w);
  });
  return ToRgba(sum);
}

Rgba AnisoSampler::Sample(const TextureFootprint& f) const {
  SelectionLanes lanes;
  selector_.Select(&f.dudx, &f.dvdx, &f.dudy, &f.dvdy, 1, lanes);
  return Blend(lanes, 0, static_cast<float>(f.u), static_cast<float>(f.v));
}

void AnisoSampler::SampleLanes(const float* dudx, const float* dvdx, const float* dudy,
                               const float* dvdy, const double* u, const double* v, int n,
                               Rgba* out) const {
  SelectionLanes lanes;
  selector_.Select(dudx, dvdx, dudy, dvdy, n, lanes);
  if (lane_reader_) {
    lane_reader_->Read(lanes, u, v, n, out);
    return;
  }
  for (int i = 0; i < n; ++i)
    out[i] = Blend(lanes, i, static_cast<float>(u[i]), static_cast<float>(v[i]));
}

void AnisoSampler::SampleMany(const TextureFootprint* in, Rgba* out, int count) const {
  // Groups of eight as arrays (the selection's lanes).
  constexpr int kGroup = SelectionLanes::kLanes;
  alignas(32) float dudx[kGroup], dvdx[kGroup], dudy[kGroup], dvdy[kGroup];
  double u[kGroup], v[kGroup];
  for (int first = 0; first < count; first += kGroup) {
    const int n = std::min(kGroup, count - first);
    for (int i = 0; i < n; ++i) {
      const TextureFootprint& f = in[first + i];
      dudx[i] = f.dudx, dvdx[i] = f.dvdx, dudy[i] = f.dudy, dvdy[i] = f.dvdy;
      u[i] = f.u, v[i] = f.v;
    }
    SampleLanes(dudx, dvdx, dudy, dvdy, u, v, n, out + first);
  }
}

void AnisoSampler::SampleBatch(const FootprintBatch& in, Rgba* out) const {
  constexpr int kGroup = SelectionLanes::kLanes;
  for (int first = 0; first < in.count; first += kGroup)
    SampleLanes(in.dudx + first, in.dvdx + first, in.dudy + first, in.dvdy + first, in.u + first,
                in.v + first, std::min(kGroup, in.count - first), out + first);
}

}  // namespace aperture
