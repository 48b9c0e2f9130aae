#include "texture/aniso_lane_reads.h"

#include <algorithm>
#include <bit>

#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#endif

namespace aperture {

#if defined(__x86_64__) && defined(__GNUC__)
namespace {

constexpr int32_t kTiltV = 1 << 8, kTilted = 1 << 14;

// 2^e as a float, for 0 <= e <= 127 (exact: the exponent bits).
__attribute__((target("avx2"))) inline __m256 PowerOfTwo(__m256i e) {
  return _mm256_castsi256_ps(_mm256_slli_epi32(_mm256_add_epi32(e, _mm256_set1_epi32(127)), 23));
}

// a + (b - a) w: the sampler's Mix, channel by channel.
__attribute__((target("avx2"))) inline __m256 Mix(__m256 a, __m256 b, __m256 w) {
  return _mm256_add_ps(a, _mm256_mul_ps(_mm256_sub_ps(b, a), w));
}

// Channel c (0..3) of eight RGBA8 texels, as floats 0..255: one integer operation and the
// conversion.
__attribute__((target("avx2"))) inline __m256 Channel(__m256i texels, int c) {
  __m256i bytes;
  if (c == 0) {
    bytes = _mm256_and_si256(texels, _mm256_set1_epi32(0xff));
  } else if (c == 3) {
    bytes = _mm256_srli_epi32(texels, 24);
  } else {
    // Byte c of each 32-bit texel to its lowest byte, zeros above (index bit 7: zero).
    const int z = -128;
    const char b = static_cast<char>(c), b4 = static_cast<char>(c + 4),
               b8 = static_cast<char>(c + 8), b12 = static_cast<char>(c + 12);
    bytes = _mm256_shuffle_epi8(
        texels, _mm256_setr_epi8(b, z, z, z, b4, z, z, z, b8, z, z, z, b12, z, z, z, b, z, z, z, b4,
                                 z, z, z, b8, z, z, z, b12, z, z, z));
  }
  return _mm256_cvtepi32_ps(bytes);
}

// Eight lanes' copies: the fields CopySample reads (texture/aniso_sampler.cc), as vectors.
struct LaneCopies {
  __m256 width, height, lambda;  // lambda 0 when untilted
  __m256i log2_w, wmask, hmask, offset;
  __m256i tilt;  // all ones where the copy is tilted to V (used when the lanes' tilts differ)
};

// Which axis is major: the same for all lanes (read as a constant), or per lane.
// kBase: the untilted base, major axis U, read without skew (plain bilinear).
enum class Tilt { kU, kV, kPerLane, kBase };

template <Tilt kTilt>
__attribute__((target("avx2"))) inline __m256 Pick(__m256 u_major, __m256 v_major, __m256 tilt) {
  if constexpr (kTilt == Tilt::kU || kTilt == Tilt::kBase) return u_major;
  if constexpr (kTilt == Tilt::kV) return v_major;
  return _mm256_blendv_ps(u_major, v_major, tilt);
}
template <Tilt kTilt>
__attribute__((target("avx2"))) inline __m256i Pick(__m256i u_major, __m256i v_major,
                                                    __m256i tilt) {
  if constexpr (kTilt == Tilt::kU || kTilt == Tilt::kBase) return u_major;
  if constexpr (kTilt == Tilt::kV) return v_major;
  return _mm256_blendv_epi8(u_major, v_major, tilt);
}

// A texel's index in its copy, at (major, minor) of each lane: (x, y) = (minor, major) on
// copies tilted to V; periodic. The copy's first texel is added by Gather.
template <Tilt kTilt>
__attribute__((target("avx2"))) inline __m256i IndexInCopy(const LaneCopies& c, __m256i major,
                                                           __m256i minor) {
  const __m256i x = Pick<kTilt>(major, minor, c.tilt);
  const __m256i y = Pick<kTilt>(minor, major, c.tilt);
  return _mm256_add_epi32(_mm256_sllv_epi32(_mm256_and_si256(y, c.hmask), c.log2_w),
                          _mm256_and_si256(x, c.wmask));
}

__attribute__((target("avx2"))) inline __m256i Gather(const uint8_t* texels, __m256i offset,
                                                      __m256i index, __m256i mask) {
  return _mm256_mask_i32gather_epi32(_mm256_setzero_si256(), reinterpret_cast<const int*>(texels),
                                     _mm256_add_epi32(offset, index), mask, 4);
}

struct LaneSums {
  __m256 c[4];
};

// Where one copy read of eight lanes takes its texels: the four texel indices inside the copy
// and the three interpolation weights (CopySample in aniso_sampler.cc, the same operations).
// They depend on the copy's shape only, so the two tilts of a cell share them.
struct ReadPlace {
  __m256i i00, i01, i10, i11;
  __m256 w1, w2, wM;
};

template <Tilt kTilt>
__attribute__((target("avx2"))) inline ReadPlace PlaceRead(const LaneCopies& c, __m256 u, __m256 v,
                                                           __m256 tg) {
  const __m256i ione = _mm256_set1_epi32(1);
  const __m256 tilt_f = _mm256_castsi256_ps(c.tilt);
  // Texel centres at +0.5 (DESIGN.md); major coordinate M along the tilt axis, minor m.
  const __m256 half = _mm256_set1_ps(0.5f), one = _mm256_set1_ps(1.0f);
  const __m256 X = _mm256_sub_ps(_mm256_mul_ps(u, c.width), half);
  const __m256 Y = _mm256_sub_ps(_mm256_mul_ps(v, c.height), half);
  const __m256 M = Pick<kTilt>(X, Y, tilt_f), m = Pick<kTilt>(Y, X, tilt_f);
  if constexpr (kTilt == Tilt::kBase) {
    // lambda = 0: both minor coordinates below are m (up to the sign of a zero m, which
    // gives the same texels and weight), so they are computed once.
    const __m256 M0 = _mm256_floor_ps(M), mf = _mm256_floor_ps(m);
    const __m256i a = _mm256_cvttps_epi32(M0), b = _mm256_cvttps_epi32(mf);
    const __m256i a1 = _mm256_add_epi32(a, ione), b1 = _mm256_add_epi32(b, ione);
    const __m256 w = _mm256_sub_ps(m, mf);
    return {IndexInCopy<kTilt>(c, a, b),
            IndexInCopy<kTilt>(c, a, b1),
            IndexInCopy<kTilt>(c, a1, b),
            IndexInCopy<kTilt>(c, a1, b1),
            w,
            w,
            _mm256_sub_ps(M, M0)};
  }
  const __m256 shift = _mm256_mul_ps(c.lambda, tg);
  const __m256 M0 = _mm256_floor_ps(M), fM = _mm256_sub_ps(M, M0);
  // seed 000, eq. 6 / 7: the minor coordinate on both neighbouring major lines.
  const __m256 m1 = _mm256_sub_ps(m, _mm256_mul_ps(fM, shift));
  const __m256 m2 = _mm256_add_ps(m, _mm256_mul_ps(_mm256_sub_ps(one, fM), shift));
  const __m256 m1f = _mm256_floor_ps(m1), m2f = _mm256_floor_ps(m2);
  const __m256i a = _mm256_cvttps_epi32(M0), b1 = _mm256_cvttps_epi32(m1f),
                b2 = _mm256_cvttps_epi32(m2f);
  const __m256i a1 = _mm256_add_epi32(a, ione);
  return {IndexInCopy<kTilt>(c, a, b1),
          IndexInCopy<kTilt>(c, a, _mm256_add_epi32(b1, ione)),
          IndexInCopy<kTilt>(c, a1, b2),
          IndexInCopy<kTilt>(c, a1, _mm256_add_epi32(b2, ione)),
          _mm256_sub_ps(m1, m1f),
          _mm256_sub_ps(m2, m2f),
          fM};
}

// The read at `place` of the copies starting at `offset`, in each lane of `mask`, added to the
// sums with `weight` (the other lanes' sums unchanged, their texels never loaded).
__attribute__((target("avx2"))) inline void AddTexels(const uint8_t* texels, const ReadPlace& p,
                                                      __m256i offset, __m256 mask, __m256 weight,
                                                      LaneSums& sums) {
  const __m256i imask = _mm256_castps_si256(mask);
  // Outside the mask the texels are 0 and every coordinate finite, so the term added there is
  // r 0 = +0: the sums stay as they are, bit for bit.
  weight = _mm256_and_ps(mask, weight);
  const __m256i t00 = Gather(texels, offset, p.i00, imask);
  const __m256i t01 = Gather(texels, offset, p.i01, imask);
  const __m256i t10 = Gather(texels, offset, p.i10, imask);
  const __m256i t11 = Gather(texels, offset, p.i11, imask);
  // seed 000, eq. 8 / 9, then the weighted sum.
  for (int k = 0; k < 4; ++k) {
    const __m256 r = Mix(Mix(Channel(t00, k), Channel(t01, k), p.w1),
                         Mix(Channel(t10, k), Channel(t11, k), p.w2), p.wM);
    sums.c[k] = _mm256_add_ps(sums.c[k], _mm256_mul_ps(r, weight));
  }
}

// Copy reads in the lanes of mask_a (the copies of c) and then of mask_b (copies of c's shape
// starting at offset_b, when kPair).
template <Tilt kTilt, bool kPair>
__attribute__((target("avx2"))) inline void AddCopyReads(const uint8_t* texels, const LaneCopies& c,
                                                         __m256i offset_b, __m256 mask_a,
                                                         __m256 mask_b, __m256 u, __m256 v,
                                                         __m256 tg, __m256 weight_a,
                                                         __m256 weight_b, LaneSums& sums) {
  const ReadPlace place = PlaceRead<kTilt>(c, u, v, tg);
  AddTexels(texels, place, c.offset, mask_a, weight_a, sums);
  if constexpr (kPair) AddTexels(texels, place, offset_b, mask_b, weight_b, sums);
}

// The fields of one copy, broadcast to the eight lanes.
__attribute__((target("avx2"))) inline LaneCopies Broadcast(const LaneReader::Copy& one) {
  LaneCopies c;
  c.width = _mm256_set1_ps(one.width), c.height = _mm256_set1_ps(one.height);
  c.lambda = _mm256_set1_ps(one.lambda);
  c.log2_w = _mm256_set1_epi32(one.log2_width), c.wmask = _mm256_set1_epi32(one.width_mask);
  c.hmask = _mm256_set1_epi32(one.height_mask), c.offset = _mm256_set1_epi32(one.offset);
  c.tilt = _mm256_setzero_si256();
  return c;
}

// The lanes' copies from their packed shapes (LaneReader::Copy::shape) and first texels.
__attribute__((target("avx2"))) inline LaneCopies Decode(__m256i shape, __m256i offset) {
  const __m256i ione = _mm256_set1_epi32(1), nibble = _mm256_set1_epi32(15);
  LaneCopies c;
  c.offset = offset;
  c.log2_w = _mm256_and_si256(shape, nibble);
  const __m256i log2_h = _mm256_and_si256(_mm256_srli_epi32(shape, 4), nibble);
  c.tilt = _mm256_cmpeq_epi32(_mm256_and_si256(shape, _mm256_set1_epi32(kTiltV)),
                              _mm256_set1_epi32(kTiltV));
  const __m256i tilted = _mm256_cmpeq_epi32(_mm256_and_si256(shape, _mm256_set1_epi32(kTilted)),
                                            _mm256_set1_epi32(kTilted));
  c.lambda = _mm256_and_ps(
      _mm256_castsi256_ps(tilted),
      PowerOfTwo(_mm256_and_si256(_mm256_srli_epi32(shape, 9), _mm256_set1_epi32(31))));
  c.wmask = _mm256_sub_epi32(_mm256_sllv_epi32(ione, c.log2_w), ione);
  c.hmask = _mm256_sub_epi32(_mm256_sllv_epi32(ione, log2_h), ione);
  c.width = PowerOfTwo(c.log2_w), c.height = PowerOfTwo(log2_h);
  return c;
}

// The directory index every lane holds, or -1 when they differ.
__attribute__((target("avx2"))) inline int Shared(__m256i copy) {
  const int first = _mm256_cvtsi256_si32(copy);
  return _mm256_movemask_epi8(_mm256_cmpeq_epi32(copy, _mm256_set1_epi32(first))) == -1 ? first
                                                                                        : -1;
}

struct CopyTables {
  const uint8_t* texels;
  const LaneReader::Copy* copies;
  int32_t box_copy;  // the first copy's directory index (the box probes read it)
};

// Field `field` (LaneReader::Copy::offset or ::shape) of each lane's copy in `mask` (0 elsewhere).
__attribute__((target("avx2"))) inline __m256i GatherField(const CopyTables& t,
                                                           int32_t LaneReader::Copy::*field,
                                                           __m256i copy, __m256i mask) {
  static_assert(sizeof(LaneReader::Copy) == 8 * sizeof(int32_t), "a record is 8 words: index << 3");
  return _mm256_mask_i32gather_epi32(_mm256_setzero_si256(), &(t.copies->*field),
                                     _mm256_slli_epi32(copy, 3), mask, 4);
}

// A copy read of eight lanes, `copy` the lanes' directory indices (0 outside `mask`).
// Neighbouring samples mostly read the same copy: then its fields are broadcast and its axis is
// a constant; else they are gathered and decoded from the packed shapes.
__attribute__((target("avx2"))) inline void AddRead(const CopyTables& t, __m256i copy, __m256 mask,
                                                    __m256 u, __m256 v, __m256 tg, __m256 weight,
                                                    LaneSums& sums) {
  const __m256i none = _mm256_setzero_si256();
  if (const int one = Shared(copy); one >= 0) {
    const LaneCopies c = Broadcast(t.copies[one]);
    if (t.copies[one].shape & kTiltV)
      AddCopyReads<Tilt::kV, false>(t.texels, c, none, mask, mask, u, v, tg, weight, weight, sums);
    else if (t.copies[one].lambda == 0.0f)
      AddCopyReads<Tilt::kBase, false>(t.texels, c, none, mask, mask, u, v, tg, weight, weight,
                                       sums);
    else
      AddCopyReads<Tilt::kU, false>(t.texels, c, none, mask, mask, u, v, tg, weight, weight, sums);
    return;
  }
  const __m256i imask = _mm256_castps_si256(mask);
  const LaneCopies c = Decode(GatherField(t, &LaneReader::Copy::shape, copy, imask),
                              GatherField(t, &LaneReader::Copy::offset, copy, imask));
  AddCopyReads<Tilt::kPerLane, false>(t.texels, c, none, mask, mask, u, v, tg, weight, weight,
                                      sums);
}

// The reads of two slots, a then b in each lane: the two tilts of a cell have one shape, so
// where every lane's two copies do, the texel indices and weights are computed once.
__attribute__((target("avx2"))) inline void AddReadPair(const CopyTables& t, __m256i copy_a,
                                                        __m256i copy_b, __m256 mask_a,
                                                        __m256 mask_b, __m256 u, __m256 v,
                                                        __m256 tg, __m256 weight_a, __m256 weight_b,
                                                        LaneSums& sums) {
  const __m256 both = _mm256_or_ps(mask_a, mask_b);
  const __m256i iboth = _mm256_castps_si256(both);
  copy_a = _mm256_and_si256(iboth, copy_a), copy_b = _mm256_and_si256(iboth, copy_b);
  const int one_a = Shared(copy_a), one_b = Shared(copy_b);
  if (one_a >= 0 && one_b >= 0 && t.copies[one_a].shape == t.copies[one_b].shape) {
    const LaneCopies c = Broadcast(t.copies[one_a]);
    const __m256i offset_b = _mm256_set1_epi32(t.copies[one_b].offset);
    if (t.copies[one_a].shape & kTiltV)
      AddCopyReads<Tilt::kV, true>(t.texels, c, offset_b, mask_a, mask_b, u, v, tg, weight_a,
                                   weight_b, sums);
    else
      AddCopyReads<Tilt::kU, true>(t.texels, c, offset_b, mask_a, mask_b, u, v, tg, weight_a,
                                   weight_b, sums);
    return;
  }
  const __m256i shape_a = GatherField(t, &LaneReader::Copy::shape, copy_a, iboth);
  const __m256i shape_b = GatherField(t, &LaneReader::Copy::shape, copy_b, iboth);
  if (_mm256_movemask_epi8(_mm256_cmpeq_epi32(shape_a, shape_b)) == -1) {
    const LaneCopies c = Decode(shape_a, GatherField(t, &LaneReader::Copy::offset, copy_a, iboth));
    const __m256i offset_b = GatherField(t, &LaneReader::Copy::offset, copy_b, iboth);
    AddCopyReads<Tilt::kPerLane, true>(t.texels, c, offset_b, mask_a, mask_b, u, v, tg, weight_a,
                                       weight_b, sums);
    return;
  }
  AddRead(t, _mm256_and_si256(_mm256_castps_si256(mask_a), copy_a), mask_a, u, v, tg, weight_a,
          sums);
  AddRead(t, _mm256_and_si256(_mm256_castps_si256(mask_b), copy_b), mask_b, u, v, tg, weight_b,
          sums);
}

// The base probes (kBox false: reads of the base) or the box probes (kBox true: reads of the
// first copy, in two rows where box_probe_rows > 0) of reading r in the lanes of `read`
// (ForEachProbe in aniso_sampler.cc, the same operations).
template <bool kBox>
__attribute__((target("avx2"))) inline void AddProbeReads(const CopyTables& t, float inv_size,
                                                          const SelectionLanes& s, int r, int n,
                                                          __m256 read, __m256 u, __m256 v,
                                                          __m256 tg, __m256 scale, LaneSums& sums) {
  const __m256 zero = _mm256_setzero_ps();
  const __m256i izero = _mm256_setzero_si256();
  const int32_t* count = kBox ? s.box_probes[r] : s.probes[r];
  const __m256i probes = _mm256_and_si256(
      _mm256_castps_si256(read), _mm256_load_si256(reinterpret_cast<const __m256i*>(count)));
  int most = 0;
  for (int i = 0; i < n; ++i) most = std::max(most, count[i] * (s.reading_weight[r][i] > 0));
  if (most == 0) return;
  // Every lane reads one untilted copy: its fields broadcast once, read as plain bilinear (what
  // AddRead does for a shared untilted copy).
  const LaneCopies copy = Broadcast(t.copies[kBox ? t.box_copy : 0]);
  // The probe fields are only set where there are probes (a stale denormal would cost a
  // microcode assist): masked before any arithmetic.
  const __m256 has = _mm256_castsi256_ps(_mm256_cmpgt_epi32(probes, izero));
  const __m256 step = _mm256_mul_ps(
      _mm256_and_ps(has, _mm256_loadu_ps(kBox ? s.box_probe_step[r] : s.probe_step[r])),
      _mm256_set1_ps(inv_size));
  const __m256 first = _mm256_mul_ps(
      _mm256_mul_ps(_mm256_set1_ps(-0.5f),
                    _mm256_cvtepi32_ps(_mm256_sub_epi32(probes, _mm256_set1_epi32(1)))),
      step);
  const __m256 w = _mm256_mul_ps(
      _mm256_and_ps(has, _mm256_loadu_ps(kBox ? s.box_probe_weight[r] : s.probe_weight[r])), scale);
  const __m256 w_end = _mm256_mul_ps(
      _mm256_and_ps(has, _mm256_loadu_ps(kBox ? s.box_probe_end_weight[r] : s.probe_end_weight[r])),
      scale);
  const __m256 along_v = _mm256_castsi256_ps(
      _mm256_cmpgt_epi32(_mm256_load_si256(reinterpret_cast<const __m256i*>(s.along_v[r])), izero));
  const __m256i last = _mm256_sub_epi32(probes, _mm256_set1_epi32(1));
  // Box probes: the rows' offset across (repeats) and the lanes read in two rows.
  const __m256 d = kBox ? _mm256_mul_ps(_mm256_and_ps(has, _mm256_loadu_ps(s.box_probe_rows[r])),
                                        _mm256_set1_ps(inv_size))
                        : zero;
  const __m256 two_rows = kBox ? _mm256_cmp_ps(d, zero, _CMP_GT_OQ) : zero;
  const bool any_two_rows = kBox && _mm256_movemask_ps(two_rows) != 0;
  for (int k = 0; k < most; ++k) {
    const __m256i kk = _mm256_set1_epi32(k);
    const __m256 mask = _mm256_castsi256_ps(_mm256_cmpgt_epi32(probes, kk));
    const __m256 major =
        _mm256_add_ps(first, _mm256_mul_ps(_mm256_set1_ps(static_cast<float>(k)), step));
    const __m256 minor = _mm256_mul_ps(major, tg);
    const __m256 end = _mm256_castsi256_ps(
        _mm256_or_si256(_mm256_cmpeq_epi32(kk, izero), _mm256_cmpeq_epi32(kk, last)));
    const __m256 wk = _mm256_blendv_ps(w, w_end, end);
    if (!any_two_rows) {
      const __m256 pu = _mm256_add_ps(u, _mm256_blendv_ps(major, minor, along_v));
      const __m256 pv = _mm256_add_ps(v, _mm256_blendv_ps(minor, major, along_v));
      AddCopyReads<Tilt::kBase, false>(t.texels, copy, izero, mask, mask, pu, pv, zero, wk, wk,
                                       sums);
      continue;
    }
    // The row -d (d = 0 in one-row lanes: minor itself, of weight wk), then the row +d.
    const __m256 half = _mm256_mul_ps(_mm256_set1_ps(0.5f), wk);
    const __m256 below = _mm256_sub_ps(minor, d), above = _mm256_add_ps(minor, d);
    const __m256 first_row = _mm256_blendv_ps(wk, half, two_rows);
    const __m256 second = _mm256_and_ps(mask, two_rows);
    AddCopyReads<Tilt::kBase, false>(t.texels, copy, izero, mask, mask,
                                     _mm256_add_ps(u, _mm256_blendv_ps(major, below, along_v)),
                                     _mm256_add_ps(v, _mm256_blendv_ps(below, major, along_v)),
                                     zero, first_row, first_row, sums);
    AddCopyReads<Tilt::kBase, false>(t.texels, copy, izero, second, second,
                                     _mm256_add_ps(u, _mm256_blendv_ps(major, above, along_v)),
                                     _mm256_add_ps(v, _mm256_blendv_ps(above, major, along_v)),
                                     zero, half, half, sums);
  }
}

// The magnified taps of the lanes of `taps` (ForEachRead in aniso_sampler.cc, the same
// operations): the first copy at the sample, then the base at +p, -p, +q, -q.
__attribute__((target("avx2"))) inline void AddMagnifiedTaps(const CopyTables& t, float inv_size,
                                                             const SelectionLanes& s, __m256 taps,
                                                             __m256 u, __m256 v, LaneSums& sums) {
  const __m256 zero = _mm256_setzero_ps(), scale = _mm256_set1_ps(1.0f / 255.0f);
  const __m256i izero = _mm256_setzero_si256();
  AddCopyReads<Tilt::kBase, false>(
      t.texels, Broadcast(t.copies[t.box_copy]), izero, taps, taps, u, v, zero,
      _mm256_mul_ps(_mm256_and_ps(taps, _mm256_load_ps(s.taps_first)), scale), zero, sums);
  const __m256 w = _mm256_mul_ps(_mm256_and_ps(taps, _mm256_load_ps(s.taps_weight)), scale);
  const __m256 inv = _mm256_set1_ps(inv_size);
  // Lanes without taps hold anything there: masked to 0 before any arithmetic.
  const __m256 pu = _mm256_mul_ps(_mm256_and_ps(taps, _mm256_load_ps(s.tap_p[0])), inv);
  const __m256 pv = _mm256_mul_ps(_mm256_and_ps(taps, _mm256_load_ps(s.tap_p[1])), inv);
  const __m256 qu = _mm256_mul_ps(_mm256_and_ps(taps, _mm256_load_ps(s.tap_q[0])), inv);
  const __m256 qv = _mm256_mul_ps(_mm256_and_ps(taps, _mm256_load_ps(s.tap_q[1])), inv);
  const LaneCopies base = Broadcast(t.copies[0]);
  AddCopyReads<Tilt::kBase, false>(t.texels, base, izero, taps, taps, _mm256_add_ps(u, pu),
                                   _mm256_add_ps(v, pv), zero, w, w, sums);
  AddCopyReads<Tilt::kBase, false>(t.texels, base, izero, taps, taps, _mm256_sub_ps(u, pu),
                                   _mm256_sub_ps(v, pv), zero, w, w, sums);
  AddCopyReads<Tilt::kBase, false>(t.texels, base, izero, taps, taps, _mm256_add_ps(u, qu),
                                   _mm256_add_ps(v, qv), zero, w, w, sums);
  AddCopyReads<Tilt::kBase, false>(t.texels, base, izero, taps, taps, _mm256_sub_ps(u, qu),
                                   _mm256_sub_ps(v, qv), zero, w, w, sums);
}

__attribute__((target("avx2"))) void ReadLanesAvx2(const CopyTables& t, float inv_size,
                                                   const SelectionLanes& s, const double* u_in,
                                                   const double* v_in, int n, Rgba* out) {
  constexpr int kLanes = SelectionLanes::kLanes;
  // Lanes [0, n) hold samples; the others read 0 and are never written out.
  const __m256 live = _mm256_castsi256_ps(
      _mm256_cmpgt_epi32(_mm256_set1_epi32(n), _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7)));
  __m256 u, v;
  if (n == kLanes) {
    u = _mm256_set_m128(_mm256_cvtpd_ps(_mm256_loadu_pd(u_in + 4)),
                        _mm256_cvtpd_ps(_mm256_loadu_pd(u_in)));
    v = _mm256_set_m128(_mm256_cvtpd_ps(_mm256_loadu_pd(v_in + 4)),
                        _mm256_cvtpd_ps(_mm256_loadu_pd(v_in)));
  } else {
    alignas(32) float u_lanes[kLanes] = {}, v_lanes[kLanes] = {};
    for (int i = 0; i < n; ++i)
      u_lanes[i] = static_cast<float>(u_in[i]), v_lanes[i] = static_cast<float>(v_in[i]);
    u = _mm256_load_ps(u_lanes), v = _mm256_load_ps(v_lanes);
  }
  const __m256 zero = _mm256_setzero_ps();
  const __m256i izero = _mm256_setzero_si256();
  LaneSums sums = {{zero, zero, zero, zero}};
  const __m256 read[2] = {
      _mm256_and_ps(live, _mm256_cmp_ps(_mm256_load_ps(s.reading_weight[0]), zero, _CMP_GT_OQ)),
      _mm256_and_ps(live, _mm256_cmp_ps(_mm256_load_ps(s.reading_weight[1]), zero, _CMP_GT_OQ))};
  const __m256 taps =
      _mm256_and_ps(live, _mm256_cmp_ps(_mm256_load_ps(s.taps_share), zero, _CMP_GT_OQ));
  // Degenerate derivatives (neither reading nor taps): the base, bilinear.
  const __m256 degenerate =
      _mm256_andnot_ps(_mm256_or_ps(_mm256_or_ps(read[0], read[1]), taps), live);
  if (_mm256_movemask_ps(degenerate) != 0)
    AddRead(t, izero, degenerate, u, v, zero, _mm256_set1_ps(1.0f / 255.0f), sums);
  if (_mm256_movemask_ps(taps) != 0) AddMagnifiedTaps(t, inv_size, s, taps, u, v, sums);
  for (int r = 0; r < 2; ++r) {
    if (_mm256_movemask_ps(read[r]) == 0) continue;
    // Lanes not read hold anything: their inputs are masked to harmless values.
    const __m256 scale = _mm256_and_ps(
        read[r], _mm256_div_ps(_mm256_load_ps(s.reading_weight[r]), _mm256_set1_ps(255.0f)));
    const __m256 tg = _mm256_and_ps(read[r], _mm256_load_ps(s.tg[r]));
    AddProbeReads<false>(t, inv_size, s, r, n, read[r], u, v, tg, scale, sums);
    AddProbeReads<true>(t, inv_size, s, r, n, read[r], u, v, tg, scale, sums);
    // The table copies, a cell's two tilts at a time: the sample's own tangent (the skew
    // interpolates between tilts).
    for (int slot = 0; slot < SelectionLanes::kSlots; slot += 2) {
      const __m256 weight_a = _mm256_load_ps(s.weight[r][slot]);
      const __m256 weight_b = _mm256_load_ps(s.weight[r][slot + 1]);
      const __m256 mask_a = _mm256_and_ps(read[r], _mm256_cmp_ps(weight_a, zero, _CMP_GT_OQ));
      const __m256 mask_b = _mm256_and_ps(read[r], _mm256_cmp_ps(weight_b, zero, _CMP_GT_OQ));
      const __m256i copy_a = _mm256_load_si256(reinterpret_cast<const __m256i*>(s.copy[r][slot]));
      const __m256i copy_b =
          _mm256_load_si256(reinterpret_cast<const __m256i*>(s.copy[r][slot + 1]));
      const int a = _mm256_movemask_ps(mask_a), b = _mm256_movemask_ps(mask_b);
      if (a != 0 && b != 0) {
        AddReadPair(t, copy_a, copy_b, mask_a, mask_b, u, v, tg,
                    _mm256_and_ps(mask_a, _mm256_mul_ps(weight_a, scale)),
                    _mm256_and_ps(mask_b, _mm256_mul_ps(weight_b, scale)), sums);
      } else if (a != 0 || b != 0) {
        const __m256 mask = a != 0 ? mask_a : mask_b;
        const __m256 weight = a != 0 ? weight_a : weight_b;
        AddRead(t, _mm256_and_si256(_mm256_castps_si256(mask), a != 0 ? copy_a : copy_b), mask, u,
                v, tg, _mm256_and_ps(mask, _mm256_mul_ps(weight, scale)), sums);
      }
    }
  }
  alignas(32) float channels[4][kLanes];
  for (int c = 0; c < 4; ++c) _mm256_store_ps(channels[c], sums.c[c]);
  for (int i = 0; i < n; ++i)
    out[i] = {channels[0][i], channels[1][i], channels[2][i], channels[3][i]};
}

}  // namespace
#endif

std::optional<LaneReader> LaneReader::For(const PrefilteredTable& table) {
#if defined(__x86_64__) && defined(__GNUC__)
  if (!__builtin_cpu_supports("avx2")) return std::nullopt;
  LaneReader reader;
  reader.texels_ = table.texels(table.base());
  reader.inv_size_ = 1.0f / static_cast<float>(table.size());
  reader.box_copy_ = static_cast<int32_t>(table.cell(0, 0).first);
  const uint64_t base = table.base().offset;
  for (const CopyEntry& e : table.directory()) {
    const uint64_t bytes = e.offset - base;
    const uint64_t last = bytes / 4 + uint64_t{e.width} * e.height;
    const bool power_of_two = std::has_single_bit(e.width) && std::has_single_bit(e.height) &&
                              (e.axis == TiltAxis::kNone || std::has_single_bit(e.lambda));
    if (e.offset < base || bytes % 4 != 0 || last >= (uint64_t{1} << 31) || !power_of_two ||
        e.width > (1u << 15) || e.height > (1u << 15) || e.lambda > (1u << 31))
      return std::nullopt;
    int32_t shape = std::countr_zero(e.width) | std::countr_zero(e.height) << 4;
    if (e.axis == TiltAxis::kV) shape |= kTiltV;
    if (e.axis != TiltAxis::kNone) shape |= std::countr_zero(e.lambda) << 9 | kTilted;
    reader.copies_.push_back({static_cast<float>(e.width), static_cast<float>(e.height),
                              e.axis == TiltAxis::kNone ? 0.0f : static_cast<float>(e.lambda),
                              std::countr_zero(e.width), static_cast<int32_t>(e.width - 1),
                              static_cast<int32_t>(e.height - 1), static_cast<int32_t>(bytes / 4),
                              shape});
  }
  return reader;
#else
  (void)table;
  return std::nullopt;
#endif
}

void LaneReader::Read(const SelectionLanes& s, const double* u, const double* v, int n,
                      Rgba* out) const {
#if defined(__x86_64__) && defined(__GNUC__)
  ReadLanesAvx2({texels_, copies_.data(), box_copy_}, inv_size_, s, u, v, n, out);
#else
  (void)s, (void)u, (void)v, (void)n, (void)out;
#endif
}

}  // namespace aperture
