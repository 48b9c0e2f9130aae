#include "texture/aniso_sampler.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>

#include "texture/footprint_batch.h"

#if defined(__SSE4_1__)
#include <smmintrin.h>
#endif
#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
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

// The base probes of a thin aperture (see AddBaseProbes): visit(u', v', weight) for each, in
// order, where they are read (a bilinear read of the base, untilted); `scale` multiplies every
// weight.
template <typename Visit>
[[gnu::always_inline]] inline void ForEachBaseProbe(const CopyBlend& blend,
                                                    const ApertureShape& shape, float u, float v,
                                                    float inv_size, float scale, Visit visit) {
  // Along the major axis, and tg times that along the minor one; in repeats.
  const float step = blend.probe_step * inv_size;
  const float first = -0.5f * static_cast<float>(blend.probes - 1) * step;
  const float tg = static_cast<float>(shape.tg);
  const float w = blend.probe_weight * scale, w_end = blend.probe_end_weight * scale;
  const bool along_u = shape.axis == TiltAxis::kU;
  for (int k = 0; k < blend.probes; ++k) {
    const float major = first + static_cast<float>(k) * step, minor = major * tg;
    visit(u + (along_u ? major : minor), v + (along_u ? minor : major),
          k == 0 || k == blend.probes - 1 ? w_end : w);
  }
}

// x = 2^e (1 + m) with 0 <= m < 1, for finite x >= 1 (std::frexp without the library call).
struct PowerOfTwoSplit {
  int e;
  double m;
};
inline PowerOfTwoSplit SplitPowerOfTwo(double x) {
  const uint64_t bits = std::bit_cast<uint64_t>(x);
  const uint64_t one_exponent = uint64_t{1023} << 52;
  const double mantissa = std::bit_cast<double>((bits & ((uint64_t{1} << 52) - 1)) | one_exponent);
  return {static_cast<int>(bits >> 52) - 1023, mantissa - 1.0};
}

// 2^e for -1022 <= e <= 1023 (std::ldexp(1.0, e) without the library call).
inline double PowerOfTwo(int e) {
  return std::bit_cast<double>(static_cast<uint64_t>(1023 + e) << 52);
}

// The copy reads of BlendReads ("jobs"): one CopySample each, with its weight in the sum.
struct ReadJobs {
  // A group of 8 samples reads at most two readings of 16 probes and 6 copies each.
  static constexpr int kMax = 8 * 2 * (16 + CopyBlend::kMaxCopies);
  int count = 0;
  alignas(32) float u[kMax], v[kMax], tg[kMax];
  alignas(32) float width[kMax], height[kMax], lambda[kMax];
  alignas(32) uint32_t width_mask[kMax], height_mask[kMax], tilt_v[kMax];  // tilt_v: ~0u or 0
  // Out of the kernel: the texel indices of the four reads and the three interpolation weights.
  alignas(32) uint32_t i00[kMax], i01[kMax], i10[kMax], i11[kMax];
  alignas(32) float w1[kMax], w2[kMax], wM[kMax];
  // Per job, for the reads: the copy's texels, the weight and the sample it adds to.
  const uint8_t* texels[kMax];
  float weight[kMax];
  int sample[kMax];
};

#if defined(__x86_64__) && defined(__GNUC__)
#define APERTURE_HAVE_AVX2_KERNEL 1

// Fetch's texel index of at(major, minor): (x, y) = (minor, major) on copies tilted to V.
__attribute__((target("avx2"))) inline __m256i ReadIndex(__m256i major, __m256i minor, __m256i tilt,
                                                         __m256i wmask, __m256i hmask,
                                                         __m256i row) {
  const __m256i x = _mm256_blendv_epi8(major, minor, tilt);
  const __m256i y = _mm256_blendv_epi8(minor, major, tilt);
  return _mm256_add_epi32(_mm256_mullo_epi32(_mm256_and_si256(y, hmask), row),
                          _mm256_and_si256(x, wmask));
}

// CopySample's addresses and weights for eight jobs: the same operations in the same order.
__attribute__((target("avx2"))) void ComputeReadsAvx2(ReadJobs& jobs) {
  const __m256 half = _mm256_set1_ps(0.5f), one = _mm256_set1_ps(1.0f);
  const __m256i ione = _mm256_set1_epi32(1);
  for (int j = 0; j < jobs.count; j += 8) {
    const __m256 X = _mm256_sub_ps(
        _mm256_mul_ps(_mm256_load_ps(jobs.u + j), _mm256_load_ps(jobs.width + j)), half);
    const __m256 Y = _mm256_sub_ps(
        _mm256_mul_ps(_mm256_load_ps(jobs.v + j), _mm256_load_ps(jobs.height + j)), half);
    const __m256i tilt = _mm256_load_si256(reinterpret_cast<const __m256i*>(jobs.tilt_v + j));
    const __m256 tilt_f = _mm256_castsi256_ps(tilt);
    const __m256 M = _mm256_blendv_ps(X, Y, tilt_f), m = _mm256_blendv_ps(Y, X, tilt_f);
    const __m256 shift =
        _mm256_mul_ps(_mm256_load_ps(jobs.lambda + j), _mm256_load_ps(jobs.tg + j));
    const __m256 M0 = _mm256_floor_ps(M), fM = _mm256_sub_ps(M, M0);
    const __m256 m1 = _mm256_sub_ps(m, _mm256_mul_ps(fM, shift));
    const __m256 m2 = _mm256_add_ps(m, _mm256_mul_ps(_mm256_sub_ps(one, fM), shift));
    const __m256 m1f = _mm256_floor_ps(m1), m2f = _mm256_floor_ps(m2);
    const __m256i a = _mm256_cvttps_epi32(M0), b1 = _mm256_cvttps_epi32(m1f),
                  b2 = _mm256_cvttps_epi32(m2f);
    const __m256i wmask = _mm256_load_si256(reinterpret_cast<const __m256i*>(jobs.width_mask + j));
    const __m256i hmask = _mm256_load_si256(reinterpret_cast<const __m256i*>(jobs.height_mask + j));
    const __m256i row = _mm256_add_epi32(wmask, ione);
    const __m256i a1 = _mm256_add_epi32(a, ione);
    _mm256_store_si256(reinterpret_cast<__m256i*>(jobs.i00 + j),
                       ReadIndex(a, b1, tilt, wmask, hmask, row));
    _mm256_store_si256(reinterpret_cast<__m256i*>(jobs.i01 + j),
                       ReadIndex(a, _mm256_add_epi32(b1, ione), tilt, wmask, hmask, row));
    _mm256_store_si256(reinterpret_cast<__m256i*>(jobs.i10 + j),
                       ReadIndex(a1, b2, tilt, wmask, hmask, row));
    _mm256_store_si256(reinterpret_cast<__m256i*>(jobs.i11 + j),
                       ReadIndex(a1, _mm256_add_epi32(b2, ione), tilt, wmask, hmask, row));
    _mm256_store_ps(jobs.w1 + j, _mm256_sub_ps(m1, m1f));
    _mm256_store_ps(jobs.w2 + j, _mm256_sub_ps(m2, m2f));
    _mm256_store_ps(jobs.wM + j, fM);
  }
}

bool HaveAvx2() { return __builtin_cpu_supports("avx2"); }
#else
void ComputeReadsAvx2(ReadJobs&) {}
bool HaveAvx2() { return false; }
#endif

}  // namespace

namespace {

// The pixel parallelogram's second moments in texels^2 and its area (see ApertureFromFootprint).
struct FootprintMoments {
  bool finite = false;
  double uu = 0, vv = 0, uv = 0, area = 0;
};

FootprintMoments MomentsOf(const TextureFootprint& f, int texture_size) {
  // seed 000, eq. 2: one pixel step of the paper's 2 x 2 aperture is half the a-scaled
  // derivative (a = 2); in texel units. The pixel's aperture is then the parallelogram
  // {s X + t Y : |s|, |t| <= 1} with X = (dUx, dVx), Y = (dUy, dVy).
  const double s = 0.5 * texture_size;
  const double dUx = f.dudx * s, dVx = f.dvdx * s, dUy = f.dudy * s, dVy = f.dvdy * s;
  FootprintMoments m;
  if (!std::isfinite(dUx) || !std::isfinite(dVx) || !std::isfinite(dUy) || !std::isfinite(dVy))
    return m;
  m.finite = true;
  m.uu = dUx * dUx + dUy * dUy;
  m.vv = dVx * dVx + dVy * dVy;
  m.uv = dUx * dVx + dUy * dVy;
  m.area = std::abs(dUx * dVy - dVx * dUy);  // |X x Y|
  return m;
}

// The table's copies are parallelograms with a pair of sides parallel to a texture axis: half
// extent H along the major axis with slope tg, half thickness L along the minor one, i.e.
// {s H (1, tg) + t L (0, 1)} (axes named major, minor). Seed 000 reads H, L and tg off the
// pixel parallelogram's bounding extents (eq. 3-4), which depend on how the footprint is turned
// against the texture: a square footprint turned 45 degrees gets a copy of twice its area.
// Our reading (issue 22): take the copy with the pixel parallelogram's second moments,
//   H^2 (1, tg) (1, tg)^T + L^2 (0, 1) (0, 1)^T = X X^T + Y Y^T,
// the Cholesky factor of the right side: H^2 = M_major, tg = M_cross / M_major,
// L = |X x Y| / H. The copy then has the pixel's area and its variance in every direction, so
// a footprint and the same footprint turned get copies of equal area and shape; along a
// texture axis (Y parallel to the major axis, or X and Y along the axes) it is the paper's.
// Along the axis of the larger moment |tg| <= 1, as the table's tilts need; along the other one
// (only inside the blend zone of ReadingsOfFootprint) |tg| stays under 1.14.
ApertureShape ShapeAlong(TiltAxis axis, const FootprintMoments& m) {
  const double major = axis == TiltAxis::kU ? m.uu : m.vv;
  ApertureShape out;
  out.axis = axis;
  out.H = std::sqrt(major);
  out.tg = m.uv / major;
  out.L = m.area / out.H;
  return out;
}

}  // namespace

ApertureShape ApertureFromFootprint(const TextureFootprint& f, int texture_size) {
  const FootprintMoments m = MomentsOf(f, texture_size);
  if (!m.finite || (m.uu == 0 && m.vv == 0)) return {};
  return ShapeAlong(m.uu >= m.vv ? TiltAxis::kU : TiltAxis::kV, m);
}

ApertureReadings ReadingsOfFootprint(const TextureFootprint& f, int texture_size) {
  const FootprintMoments m = MomentsOf(f, texture_size);
  ApertureReadings out;
  if (!m.finite || (m.uu == 0 && m.vv == 0)) return out;
  // r = 1 along U, -1 along V, 0 on a diagonal; U's weight goes 0 -> 1 across |r| < zone.
  const double r = (m.uu - m.vv) / (m.uu + m.vv);
  const double along_u = std::clamp(0.5 + r / (2 * kAxisBlendZone), 0.0, 1.0);
  if (along_u > 0) {
    out.shape[out.count] = ShapeAlong(TiltAxis::kU, m);
    out.weight[out.count++] = static_cast<float>(along_u);
  }
  if (along_u < 1) {
    out.shape[out.count] = ShapeAlong(TiltAxis::kV, m);
    out.weight[out.count++] = static_cast<float>(1.0 - along_u);
  }
  return out;
}

namespace {

// Base probes carry the thin apertures up to this half-extent, fading out to twice it.
constexpr double kProbeHalfExtent = 4.0;
// Probes are this many texels apart along the long side once more than two are needed.
constexpr double kProbeSpacing = 1.0;

// Below L = 1 the table's thinnest copies are up to twice too thick across the long side: the
// paper's table stops there. This mixes in bilinear probes of the base, spread along the long
// side, so that the blend's variances are the aperture's own (box of half-sides H and L on the
// bilinear texture: H^2 / 3 + 1/6 along the long side, L^2 / 3 + 1/6 across it, in texels^2).
// Across, a probe carries 1/6 (the bilinear tent alone) and the copies of L = 1 carry
// 1/3 + 1/6, so the copies keep the share L^2 and the probes take 1 - L^2. Along the long side
// the probes' positions must have the variance T (their own tents add the 1/6):
//  - H >= 1: the copies are the table's for (H, 1), T = H^2 / 3, the long side's box;
//  - H < 1: the first copy (2 x 2 box) alone with the share L^2, and T = (H^2 - L^2) /
//    (3 (1 - L^2)) makes the variance along the long side H^2 / 3 + 1/6 too. At H = 1 both are
//    1/3; at H = L, T = 0 and the blend is the paper's (base and first copy by H^2).
// Every change is continuous (issue 22, part 3): under T = s^2 / 4 (s = kProbeSpacing) two
// probes at +-sqrt(T), which meet at the centre as T -> 0; above it 2J probes s apart, the
// outer two of weight e growing from 0 (where they appear) to the others' (where the next pair
// appears), e set so that the variance is T. The probes fade out between kProbeHalfExtent and
// twice it.
void AddBaseProbes(const ApertureShape& shape, CopyBlend& blend) {
  const double H = shape.H, L = std::min(shape.L, shape.H);
  if (!(L < 1.0) || H >= 2 * kProbeHalfExtent) return;
  // In float from here: this runs for every thin sample and its divisions showed in profiles.
  const float share = static_cast<float>(std::min(1.0, 2.0 - H / kProbeHalfExtent) * (1.0 - L * L));
  const float s2 = static_cast<float>(kProbeSpacing * kProbeSpacing);
  float T = static_cast<float>(H * H) * (1.0f / 3.0f);
  if (H < 1.0) {
    T = static_cast<float>((H * H - L * L) / (3.0 * (1.0 - L * L)));
    blend.count = 1;
    blend.copy[0] = blend.copy[1];
    blend.weight[0] = 1.0f;
  }
  if (T <= 0.25f * s2) {
    blend.probes = 2;
    blend.probe_step = 2.0f * std::sqrt(T);
    blend.probe_end_weight = 0.5f * share;
  } else {
    const float t = T / s2;  // in units of the spacing^2
    // The smallest J whose 2J evenly weighted probes reach t: (4 J^2 - 1) / 12 >= t.
    const int J = std::max(2, static_cast<int>(std::ceil(0.5f * std::sqrt(12.0f * t + 1.0f))));
    // The 2 (J - 1) inner probes alone have the variance A (e = 0); e solves
    // A + 2 e ((J - 1/2)^2 - A) = t with inner weights (1 - 2 e) / (2 (J - 1)), and
    // (J - 1/2)^2 - A = J (2J - 1) / 3.
    const float Jf = static_cast<float>(J);
    const float A = (4.0f * (Jf - 1.0f) * (Jf - 1.0f) - 1.0f) * (1.0f / 12.0f);
    const float e = std::clamp(1.5f * (t - A) / (Jf * (2.0f * Jf - 1.0f)), 0.0f, 0.5f / Jf);
    blend.probes = 2 * J;
    blend.probe_step = static_cast<float>(kProbeSpacing);
    blend.probe_end_weight = e * share;
    blend.probe_weight = (1.0f - 2.0f * e) / (2.0f * (Jf - 1.0f)) * share;
  }
  for (int c = 0; c < blend.count; ++c) blend.weight[c] *= 1.0f - share;
}

// Between the two tilts nearest the tangent, the next one's weight by the fraction of the way
// from the lower tilt's centre to the next one's: the nearer tilt alone within a quarter of the
// spacing of its centre, a linear blend over the middle half. Continuous, and half the samples
// read one tilt (a blend over the whole spacing cost 2 ms more a demo frame for 0.03 dB).
inline float NextTiltWeight(float fraction) {
  return std::clamp(2.0f * fraction - 0.5f, 0.0f, 1.0f);
}

// seed 000, eq. 5 (SelectTableCopies), with the two nearest tilts of each cell.
[[gnu::always_inline]] inline CopyBlend TableCopies(const PrefilteredTable& table,
                                                    const ApertureShape& shape) {
  CopyBlend blend;
  if (shape.axis == TiltAxis::kNone || !(shape.H > 0.0)) {
    blend.magnify = true;  // degenerate derivatives: the base, bilinear
    return blend;
  }
  if (shape.H < 1.0) {
    // Magnification, between the base (bilinear texels, H = 0) and the first copy (the box of
    // 2 x 2 texels, H = L = 1). The paper falls back to the base for all H < 1; blending with
    // weight H^2 gives the blend the variance of a box of 2H texels, so the blur grows
    // continuously up to the table (docs/BENCHMARKS.md, issue 3, measures both).
    const float m = static_cast<float>(shape.H * shape.H);
    blend.count = 2;
    blend.copy[0] = 0;
    blend.weight[0] = 1.0f - m;
    blend.copy[1] = table.cell(0, 0).first;
    blend.weight[1] = m;
    return blend;
  }
  const int n = table.log2_size();
  // L between 1 (the thinnest copy) and H; raised to H / 2^(n-1) where lambda is frozen. Powers
  // of two from their bits and products (exact), not ldexp: this runs once per sample.
  const double H = std::min(shape.H, PowerOfTwo(3 * n));
  const double L = std::clamp(shape.L, std::max(1.0, H * PowerOfTwo(1 - n)), H);
  // seed 000, eq. 5: H = 2^eH (1 + M_H), L = 2^eL (1 + M_L).
  const auto [eH, mH] = SplitPowerOfTwo(H);
  const auto [eL, mL0] = SplitPowerOfTwo(L);
  // Tilt k of a cell of lambda copies, tg_k = (2k + 1) / half - 1 (half = lambda / 2), sits at
  // k = (tg + 1) half / 2 - 1/2 on the tilt axis.
  const float tilt_position = static_cast<float>((shape.tg + 1.0) * 0.5);
  const uint32_t v_offset = shape.axis == TiltAxis::kV ? 1 : 0;
  const PrefilteredTable::Cell* cells = &table.cell(0, 0);
  auto add = [&](uint32_t copy, float weight) {
    if (!(weight > 0.0f)) return;
    blend.copy[blend.count] = copy;
    blend.weight[blend.count++] = weight;
  };
  auto add_cell = [&](int j, int i, float weight) {
    const PrefilteredTable::Cell& c = cells[j * n + i];
    const int half = static_cast<int>(c.lambda / 2);  // 0 for the one untilted copy (lambda 1)
    if (half <= 1) return add(c.first + v_offset * static_cast<uint32_t>(half), weight);
    // Beyond the outer tilts' centres the outer tilt alone (the skewed read follows tg).
    const float k = std::clamp(tilt_position * static_cast<float>(half) - 0.5f, 0.0f,
                               static_cast<float>(half - 1));
    const int k0 = std::min(static_cast<int>(k), half - 2);
    const float next = NextTiltWeight(k - static_cast<float>(k0));
    const uint32_t first = c.first + v_offset * static_cast<uint32_t>(half) + k0;
    add(first, weight * (1.0f - next));
    add(first + 1, weight * next);
  };
  if (eL >= n) {  // L >= 2^n: the aperture covers whole periods both ways
    add_cell(n, std::min(eH - n, n - 1), 1.0f);
    return blend;
  }
  int i = eH - eL;
  double mL = mL0, mh = mH;
  if (i >= n - 1) {  // lambda frozen: no cell (eL, eH + 1); L was raised so that M_H = M_L
    i = n - 1;
    mh = std::min(mh, mL);
  }
  // R1, then R3 = (eH + 1, eL) when M_H >= M_L, else R4 = (eH, eL + 1), then R2 (the
  // comparison is a coin toss from sample to sample).
  const bool r3 = mh >= mL;
  add_cell(eL, i, static_cast<float>(1.0 - std::max(mh, mL)));
  add_cell(r3 ? eL : eL + 1, r3 ? i + 1 : i - 1, static_cast<float>(std::abs(mh - mL)));
  add_cell(eL + 1, i, static_cast<float>(std::min(mh, mL)));
  return blend;
}

}  // namespace

CopyBlend SelectTableCopies(const PrefilteredTable& table, const ApertureShape& shape) {
  return TableCopies(table, shape);
}

// Out of line: inlined into SampleMany's loop it measured slower (24 against 18 ns a sample).
[[gnu::noinline]] CopyBlend SelectCopies(const PrefilteredTable& table,
                                         const ApertureShape& shape) {
  CopyBlend blend = TableCopies(table, shape);
  if (!blend.magnify) AddBaseProbes(shape, blend);
  return blend;
}

AnisoSampler::CopyLayout AnisoSampler::LayoutOf(const CopyEntry& e) const {
  return {table_.texels(e),
          static_cast<float>(e.width),
          static_cast<float>(e.height),
          e.axis == TiltAxis::kNone ? 0.0f : static_cast<float>(e.lambda),
          e.width - 1,
          e.height - 1,
          e.axis == TiltAxis::kV};
}

AnisoSampler::AnisoSampler(PrefilteredTable table) : table_(std::move(table)) {
  layouts_.reserve(table_.directory().size());
  read_kernel_ = HaveAvx2();
  for (const CopyEntry& e : table_.directory()) {
    layouts_.push_back(LayoutOf(e));
    // The kernel's texel indices are 32-bit.
    if (uint64_t{e.width} * e.height >= (uint64_t{1} << 31)) read_kernel_ = false;
  }
}

Rgba AnisoSampler::SampleCopy(const CopyEntry& e, double u, double v, double tg) const {
  const V4 r =
      CopySample(LayoutOf(e), static_cast<float>(u), static_cast<float>(v), static_cast<float>(tg));
  return ToRgba(AddScaled(Zero(), r, 1.0f / 255.0f));
}

void AnisoSampler::Select(const TextureFootprint& f, Selection& out) const {
  out.readings = ReadingsOfFootprint(f, table_.size());
  for (int r = 0; r < out.readings.count; ++r)
    out.blend[r] = SelectCopies(table_, out.readings.shape[r]);
}

template <typename Visit>
void AnisoSampler::ForEachRead(const TextureFootprint& f, const Selection& s, Visit visit) const {
  const float u = static_cast<float>(f.u), v = static_cast<float>(f.v);
  const float inv_size = 1.0f / table_.size();
  if (s.readings.count == 0) {
    visit(layouts_[0], u, v, 0.0f, 1.0f / 255.0f);  // degenerate derivatives: the base, bilinear
    return;
  }
  for (int r = 0; r < s.readings.count; ++r) {
    const CopyBlend& blend = s.blend[r];
    const ApertureShape& shape = s.readings.shape[r];
    const float scale = s.readings.weight[r] / 255.0f;
    if (blend.magnify) {
      visit(layouts_[0], u, v, 0.0f, scale);
      continue;
    }
    ForEachBaseProbe(blend, shape, u, v, inv_size, scale,
                     [&](float pu, float pv, float w) { visit(layouts_[0], pu, pv, 0.0f, w); });
    // The sample's own tangent: the skew interpolates between tilts (seed 000, eq. 6-9).
    const float tg = static_cast<float>(shape.tg);
    for (int c = 0; c < blend.count; ++c)
      visit(layouts_[blend.copy[c]], u, v, tg, blend.weight[c] * scale);
  }
}

Rgba AnisoSampler::Sample(const TextureFootprint& f) const {
  Selection s;
  Select(f, s);
  return Blend(f, s);
}

template <typename FootprintOf>
void AnisoSampler::SampleGroups(FootprintOf footprint_of, Rgba* out, int count) const {
  // Groups of 4 to 32 measured the same on the demo; a third phase (all texel addresses of the
  // group before any read) gained nothing.
  constexpr int kGroup = 8;
  TextureFootprint footprints[kGroup];
  for (int first = 0; first < count; first += kGroup) {
    const int n = std::min(kGroup, count - first);
    for (int i = 0; i < n; ++i) footprints[i] = footprint_of(first + i);
    if (read_kernel_) {
      BlendReads(footprints, n, out + first);
      continue;
    }
    for (int i = 0; i < n; ++i) out[first + i] = Sample(footprints[i]);
  }
}

void AnisoSampler::BlendReads(const TextureFootprint* f, int n, Rgba* out) const {
  ReadJobs jobs;  // uninitialised arrays: each job is written before the kernel reads it
  // Blend's reads in Blend's order, each sample's selected just before its reads are listed.
  Selection selection;
  for (int i = 0; i < n; ++i) {
    Select(f[i], selection);
    ForEachRead(f[i], selection,
                [&](const CopyLayout& c, float u, float v, float tg, float weight) {
                  const int j = jobs.count++;
                  jobs.u[j] = u, jobs.v[j] = v, jobs.tg[j] = tg;
                  jobs.width[j] = c.width, jobs.height[j] = c.height, jobs.lambda[j] = c.lambda;
                  jobs.width_mask[j] = c.width_mask, jobs.height_mask[j] = c.height_mask;
                  jobs.tilt_v[j] = c.tilt_v ? ~0u : 0u;
                  jobs.texels[j] = c.texels, jobs.weight[j] = weight, jobs.sample[j] = i;
                });
  }
  // Whole vectors: the padding repeats the first job (its results are not read).
  const int jobs_count = jobs.count;
  while (jobs.count % 8 != 0) {
    const int j = jobs.count++;
    jobs.u[j] = jobs.u[0], jobs.v[j] = jobs.v[0], jobs.tg[j] = jobs.tg[0];
    jobs.width[j] = jobs.width[0], jobs.height[j] = jobs.height[0];
    jobs.lambda[j] = jobs.lambda[0], jobs.width_mask[j] = jobs.width_mask[0];
    jobs.height_mask[j] = jobs.height_mask[0], jobs.tilt_v[j] = jobs.tilt_v[0];
  }
  ComputeReadsAvx2(jobs);
  // The reads and sums, sample by sample in job order (CopySample's Mix, then AddScaled).
  int j = 0;
  for (int i = 0; i < n; ++i) {
    V4 sum = Zero();
    for (; j < jobs_count && jobs.sample[j] == i; ++j) {
      const uint8_t* t = jobs.texels[j];
      const V4 r = Mix(Mix(LoadTexel(t + 4 * size_t{jobs.i00[j]}),
                           LoadTexel(t + 4 * size_t{jobs.i01[j]}), jobs.w1[j]),
                       Mix(LoadTexel(t + 4 * size_t{jobs.i10[j]}),
                           LoadTexel(t + 4 * size_t{jobs.i11[j]}), jobs.w2[j]),
                       jobs.wM[j]);
      sum = AddScaled(sum, r, jobs.weight[j]);
    }
    out[i] = ToRgba(sum);
  }
}

void AnisoSampler::SampleMany(const TextureFootprint* in, Rgba* out, int count) const {
  SampleGroups([in](int i) { return in[i]; }, out, count);
}

void AnisoSampler::SampleBatch(const FootprintBatch& in, Rgba* out) const {
  SampleGroups([&in](int i) { return in.At(i); }, out, in.count);
}

Rgba AnisoSampler::Blend(const TextureFootprint& f, const Selection& s) const {
  V4 sum = Zero();
  ForEachRead(f, s, [&](const CopyLayout& c, float u, float v, float tg, float weight) {
    sum = AddScaled(sum, CopySample(c, u, v, tg), weight);
  });
  return ToRgba(sum);
}

}  // namespace aperture
