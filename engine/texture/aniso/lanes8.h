// Eight lanes of float or int32 with two back ends of the same operations: `portable` (a loop
// per operation, which the compiler vectorises for the baseline ISA) and `avx2` (one AVX2
// instruction each, compiled under a target pragma so the rest of the build stays baseline).
// A kernel is written once over F, I and M and included once per back end (the .cc files of
// this folder), then chosen at run time. Both back ends give the same bits: every operation is
// IEEE-exact per lane (no fused multiply-add, no approximations), and the few that are not
// defined for every input in C++ (a float to int conversion out of range, int overflow) are
// written to do what the instruction does.
#pragma once

#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>

#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#define APERTURE_LANES8_AVX2 1
// Functions defined between these are compiled for AVX2 (the avx2 back end and the kernels
// included for it); the rest of a file stays baseline.
#if defined(__clang__)
#define APERTURE_LANES8_AVX2_BEGIN \
  _Pragma("clang attribute push(__attribute__((target(\"avx2\"))), apply_to = function)")
#define APERTURE_LANES8_AVX2_END _Pragma("clang attribute pop")
#else
#define APERTURE_LANES8_AVX2_BEGIN _Pragma("GCC push_options") _Pragma("GCC target(\"avx2\")")
#define APERTURE_LANES8_AVX2_END _Pragma("GCC pop_options")
#endif
#endif

namespace aperture::lanes8 {

inline constexpr int kLanes = 8;

namespace portable {

struct F {
  float v[kLanes];
};
struct I {
  int32_t v[kLanes];
};
struct M {  // all bits set where true
  int32_t v[kLanes];
};

#define APERTURE_LANES8_EACH for (int i = 0; i < kLanes; ++i)

inline F Set(float x) {
  F r;
  APERTURE_LANES8_EACH r.v[i] = x;
  return r;
}
inline I SetI(int32_t x) {
  I r;
  APERTURE_LANES8_EACH r.v[i] = x;
  return r;
}
inline F Load(const float* p) {
  F r;
  APERTURE_LANES8_EACH r.v[i] = p[i];
  return r;
}
inline I LoadI(const int32_t* p) {
  I r;
  APERTURE_LANES8_EACH r.v[i] = p[i];
  return r;
}
inline I LoadI(const uint32_t* p) {
  I r;
  APERTURE_LANES8_EACH r.v[i] = static_cast<int32_t>(p[i]);
  return r;
}
inline void Store(float* p, F a) { APERTURE_LANES8_EACH p[i] = a.v[i]; }
inline void StoreI(int32_t* p, I a) { APERTURE_LANES8_EACH p[i] = a.v[i]; }
inline void StoreI(uint32_t* p, I a) { APERTURE_LANES8_EACH p[i] = static_cast<uint32_t>(a.v[i]); }

#define APERTURE_LANES8_BINARY(T, op, expr) \
  inline T operator op(T a, T b) {          \
    T r;                                    \
    APERTURE_LANES8_EACH r.v[i] = expr;     \
    return r;                               \
  }
APERTURE_LANES8_BINARY(F, +, a.v[i] + b.v[i])
APERTURE_LANES8_BINARY(F, -, a.v[i] - b.v[i])
APERTURE_LANES8_BINARY(F, *, a.v[i] * b.v[i])
APERTURE_LANES8_BINARY(F, /, a.v[i] / b.v[i])
// Wrapping, as the instructions do (signed overflow is undefined in C++).
APERTURE_LANES8_BINARY(I, +,
                       static_cast<int32_t>(static_cast<uint32_t>(a.v[i]) +
                                            static_cast<uint32_t>(b.v[i])))
APERTURE_LANES8_BINARY(I, -,
                       static_cast<int32_t>(static_cast<uint32_t>(a.v[i]) -
                                            static_cast<uint32_t>(b.v[i])))
APERTURE_LANES8_BINARY(I, *,
                       static_cast<int32_t>(static_cast<uint32_t>(a.v[i]) *
                                            static_cast<uint32_t>(b.v[i])))
APERTURE_LANES8_BINARY(I, &, a.v[i] & b.v[i])
APERTURE_LANES8_BINARY(I, |, a.v[i] | b.v[i])
APERTURE_LANES8_BINARY(M, &, a.v[i] & b.v[i])
APERTURE_LANES8_BINARY(M, |, a.v[i] | b.v[i])
#undef APERTURE_LANES8_BINARY

#define APERTURE_LANES8_COMPARE(T, op)                       \
  inline M operator op(T a, T b) {                           \
    M r;                                                     \
    APERTURE_LANES8_EACH r.v[i] = a.v[i] op b.v[i] ? -1 : 0; \
    return r;                                                \
  }
APERTURE_LANES8_COMPARE(F, <)
APERTURE_LANES8_COMPARE(F, <=)
APERTURE_LANES8_COMPARE(F, >)
APERTURE_LANES8_COMPARE(F, >=)
APERTURE_LANES8_COMPARE(F, ==)
APERTURE_LANES8_COMPARE(I, >)
APERTURE_LANES8_COMPARE(I, ==)
#undef APERTURE_LANES8_COMPARE

// x where m is set, else 0.
inline F Keep(M m, F x) {
  F r;
  APERTURE_LANES8_EACH r.v[i] = m.v[i] < 0 ? x.v[i] : 0.0f;
  return r;
}
// ~a & b.
inline M AndNot(M a, M b) {
  M r;
  APERTURE_LANES8_EACH r.v[i] = ~a.v[i] & b.v[i];
  return r;
}
// Bit i set where lane i is true.
inline int Bits(M m) {
  int bits = 0;
  APERTURE_LANES8_EACH bits |= (m.v[i] < 0 ? 1 : 0) << i;
  return bits;
}
// yes where m is set, else no (F or I).
template <typename T>
inline T Select(M m, T yes, T no) {
  T r;
  APERTURE_LANES8_EACH r.v[i] = m.v[i] < 0 ? yes.v[i] : no.v[i];
  return r;
}
// a < b ? a : b and a > b ? a : b, as minps and maxps (b where either is NaN), and pminsd and
// pmaxsd for I.
template <typename T>
inline T Min(T a, T b) {
  T r;
  APERTURE_LANES8_EACH r.v[i] = a.v[i] < b.v[i] ? a.v[i] : b.v[i];
  return r;
}
template <typename T>
inline T Max(T a, T b) {
  T r;
  APERTURE_LANES8_EACH r.v[i] = a.v[i] > b.v[i] ? a.v[i] : b.v[i];
  return r;
}
#define APERTURE_LANES8_UNARY(name, function)       \
  inline F name(F a) {                              \
    F r;                                            \
    APERTURE_LANES8_EACH r.v[i] = function(a.v[i]); \
    return r;                                       \
  }
APERTURE_LANES8_UNARY(Sqrt, std::sqrt)
APERTURE_LANES8_UNARY(Abs, std::abs)
APERTURE_LANES8_UNARY(Ceil, std::ceil)
APERTURE_LANES8_UNARY(Floor, std::floor)
#undef APERTURE_LANES8_UNARY
// Truncation; INT32_MIN out of range and for NaN, as cvttps2dq.
inline I Truncate(F a) {
  I r;
  APERTURE_LANES8_EACH r.v[i] =
      a.v[i] > -2147483904.0f && a.v[i] < 2147483648.0f ? static_cast<int32_t>(a.v[i]) : INT32_MIN;
  return r;
}
inline F ToFloat(I a) {
  F r;
  APERTURE_LANES8_EACH r.v[i] = static_cast<float>(a.v[i]);
  return r;
}
inline I BitsOf(F a) {
  I r;
  APERTURE_LANES8_EACH r.v[i] = std::bit_cast<int32_t>(a.v[i]);
  return r;
}
inline F FloatOf(I a) {
  F r;
  APERTURE_LANES8_EACH r.v[i] = std::bit_cast<float>(a.v[i]);
  return r;
}
inline M MaskOf(F a) { return std::bit_cast<M>(BitsOf(a)); }
inline F FloatOf(M m) { return std::bit_cast<F>(m); }
template <int kBits>
inline I ShiftRightLogical(I a) {
  I r;
  APERTURE_LANES8_EACH r.v[i] = static_cast<int32_t>(static_cast<uint32_t>(a.v[i]) >> kBits);
  return r;
}
inline I Gather(const int32_t* base, I index) {
  I r;
  APERTURE_LANES8_EACH r.v[i] = base[index.v[i]];
  return r;
}
inline I Gather(const uint32_t* base, I index) {
  I r;
  APERTURE_LANES8_EACH r.v[i] = static_cast<int32_t>(base[index.v[i]]);
  return r;
}
// table[index & 7] of an eight-entry table.
inline F Lookup8(const float* table, I index) {
  F r;
  APERTURE_LANES8_EACH r.v[i] = table[index.v[i] & 7];
  return r;
}
inline int32_t First(I a) { return a.v[0]; }
inline I ShiftRightLogical(I a, int bits) {
  I r;
  APERTURE_LANES8_EACH r.v[i] = static_cast<int32_t>(static_cast<uint32_t>(a.v[i]) >> bits);
  return r;
}
inline I IOf(M m) { return std::bit_cast<I>(m); }
inline M MOf(I a) { return std::bit_cast<M>(a); }
// 0, 1, ..., 7.
inline I LaneIndex() {
  I r;
  APERTURE_LANES8_EACH r.v[i] = i;
  return r;
}
inline F FromDoubles(const double* p) {
  F r;
  APERTURE_LANES8_EACH r.v[i] = static_cast<float>(p[i]);
  return r;
}
template <int kBits>
inline I ShiftLeft(I a) {
  I r;
  APERTURE_LANES8_EACH r.v[i] = static_cast<int32_t>(static_cast<uint32_t>(a.v[i]) << kBits);
  return r;
}
// a << count per lane (0 for counts above 31, as vpsllvd).
inline I ShiftLeft(I a, I count) {
  I r;
  APERTURE_LANES8_EACH r.v[i] =
      static_cast<uint32_t>(count.v[i]) > 31
          ? 0
          : static_cast<int32_t>(static_cast<uint32_t>(a.v[i]) << count.v[i]);
  return r;
}
// Byte c (0..3) of each lane, as an int 0..255.
inline I Byte(I a, int c) { return ShiftRightLogical(a, 8 * c) & SetI(0xff); }
// base[index] where mask is set, 0 elsewhere (nothing read there).
inline I Gather(const int32_t* base, I index, M mask) {
  I r;
  APERTURE_LANES8_EACH r.v[i] = mask.v[i] < 0 ? base[index.v[i]] : 0;
  return r;
}
// The 32-bit words at bytes + 4 index where mask is set, 0 elsewhere.
inline I GatherWords(const uint8_t* bytes, I index, M mask) {
  I r;
  APERTURE_LANES8_EACH {
    r.v[i] = 0;
    if (mask.v[i] < 0) std::memcpy(&r.v[i], bytes + 4 * static_cast<size_t>(index.v[i]), 4);
  }
  return r;
}
inline bool AllEqual(I a) { return Bits(a == SetI(First(a))) == (1 << kLanes) - 1; }

#undef APERTURE_LANES8_EACH

}  // namespace portable

#if defined(APERTURE_LANES8_AVX2)
APERTURE_LANES8_AVX2_BEGIN
namespace avx2 {

struct F {
  __m256 v;
};
struct I {
  __m256i v;
};
struct M {  // all bits set where true
  __m256 v;
};

inline F Set(float x) { return {_mm256_set1_ps(x)}; }
inline I SetI(int32_t x) { return {_mm256_set1_epi32(x)}; }
inline F Load(const float* p) { return {_mm256_loadu_ps(p)}; }
inline I LoadI(const int32_t* p) {
  return {_mm256_loadu_si256(reinterpret_cast<const __m256i*>(p))};
}
inline I LoadI(const uint32_t* p) {
  return {_mm256_loadu_si256(reinterpret_cast<const __m256i*>(p))};
}
inline void Store(float* p, F a) { _mm256_storeu_ps(p, a.v); }
inline void StoreI(int32_t* p, I a) { _mm256_storeu_si256(reinterpret_cast<__m256i*>(p), a.v); }
inline void StoreI(uint32_t* p, I a) { _mm256_storeu_si256(reinterpret_cast<__m256i*>(p), a.v); }

inline F operator+(F a, F b) { return {_mm256_add_ps(a.v, b.v)}; }
inline F operator-(F a, F b) { return {_mm256_sub_ps(a.v, b.v)}; }
inline F operator*(F a, F b) { return {_mm256_mul_ps(a.v, b.v)}; }
inline F operator/(F a, F b) { return {_mm256_div_ps(a.v, b.v)}; }
inline I operator+(I a, I b) { return {_mm256_add_epi32(a.v, b.v)}; }
inline I operator-(I a, I b) { return {_mm256_sub_epi32(a.v, b.v)}; }
inline I operator*(I a, I b) { return {_mm256_mullo_epi32(a.v, b.v)}; }
inline I operator&(I a, I b) { return {_mm256_and_si256(a.v, b.v)}; }
inline I operator|(I a, I b) { return {_mm256_or_si256(a.v, b.v)}; }
inline M operator&(M a, M b) { return {_mm256_and_ps(a.v, b.v)}; }
inline M operator|(M a, M b) { return {_mm256_or_ps(a.v, b.v)}; }

inline M operator<(F a, F b) { return {_mm256_cmp_ps(a.v, b.v, _CMP_LT_OQ)}; }
inline M operator<=(F a, F b) { return {_mm256_cmp_ps(a.v, b.v, _CMP_LE_OQ)}; }
inline M operator>(F a, F b) { return {_mm256_cmp_ps(a.v, b.v, _CMP_GT_OQ)}; }
inline M operator>=(F a, F b) { return {_mm256_cmp_ps(a.v, b.v, _CMP_GE_OQ)}; }
inline M operator==(F a, F b) { return {_mm256_cmp_ps(a.v, b.v, _CMP_EQ_OQ)}; }
inline M operator>(I a, I b) { return {_mm256_castsi256_ps(_mm256_cmpgt_epi32(a.v, b.v))}; }
inline M operator==(I a, I b) { return {_mm256_castsi256_ps(_mm256_cmpeq_epi32(a.v, b.v))}; }

inline F Keep(M m, F x) { return {_mm256_and_ps(m.v, x.v)}; }
inline M AndNot(M a, M b) { return {_mm256_andnot_ps(a.v, b.v)}; }
inline int Bits(M m) { return _mm256_movemask_ps(m.v); }
inline F Select(M m, F yes, F no) { return {_mm256_blendv_ps(no.v, yes.v, m.v)}; }
inline I Select(M m, I yes, I no) {
  return {_mm256_blendv_epi8(no.v, yes.v, _mm256_castps_si256(m.v))};
}
inline F Min(F a, F b) { return {_mm256_min_ps(a.v, b.v)}; }
inline F Max(F a, F b) { return {_mm256_max_ps(a.v, b.v)}; }
inline I Min(I a, I b) { return {_mm256_min_epi32(a.v, b.v)}; }
inline I Max(I a, I b) { return {_mm256_max_epi32(a.v, b.v)}; }
inline F Sqrt(F a) { return {_mm256_sqrt_ps(a.v)}; }
inline F Abs(F a) { return {_mm256_andnot_ps(_mm256_set1_ps(-0.0f), a.v)}; }
inline F Ceil(F a) { return {_mm256_ceil_ps(a.v)}; }
inline I Truncate(F a) { return {_mm256_cvttps_epi32(a.v)}; }
inline F ToFloat(I a) { return {_mm256_cvtepi32_ps(a.v)}; }
inline I BitsOf(F a) { return {_mm256_castps_si256(a.v)}; }
inline F FloatOf(I a) { return {_mm256_castsi256_ps(a.v)}; }
inline M MaskOf(F a) { return {a.v}; }
inline F FloatOf(M m) { return {m.v}; }
template <int kBits>
inline I ShiftRightLogical(I a) {
  return {_mm256_srli_epi32(a.v, kBits)};
}
inline I Gather(const int32_t* base, I index) { return {_mm256_i32gather_epi32(base, index.v, 4)}; }
inline I Gather(const uint32_t* base, I index) {
  return {_mm256_i32gather_epi32(reinterpret_cast<const int*>(base), index.v, 4)};
}
inline F Lookup8(const float* table, I index) {
  return {_mm256_permutevar8x32_ps(_mm256_loadu_ps(table), index.v)};
}
inline int32_t First(I a) { return _mm256_cvtsi256_si32(a.v); }
inline I IOf(M m) { return {_mm256_castps_si256(m.v)}; }
inline M MOf(I a) { return {_mm256_castsi256_ps(a.v)}; }
inline I LaneIndex() { return {_mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7)}; }
inline F Floor(F a) { return {_mm256_floor_ps(a.v)}; }
inline F FromDoubles(const double* p) {
  return {_mm256_set_m128(_mm256_cvtpd_ps(_mm256_loadu_pd(p + 4)),
                          _mm256_cvtpd_ps(_mm256_loadu_pd(p)))};
}
template <int kBits>
inline I ShiftLeft(I a) {
  return {_mm256_slli_epi32(a.v, kBits)};
}
inline I ShiftLeft(I a, I count) { return {_mm256_sllv_epi32(a.v, count.v)}; }
inline I Byte(I a, int c) {
  if (c == 0) return {_mm256_and_si256(a.v, _mm256_set1_epi32(0xff))};
  if (c == 3) return {_mm256_srli_epi32(a.v, 24)};
  // Byte c of each 32-bit lane to its lowest byte, zeros above (index bit 7: zero).
  const char z = -128, b = static_cast<char>(c), b4 = static_cast<char>(c + 4),
             b8 = static_cast<char>(c + 8), b12 = static_cast<char>(c + 12);
  return {_mm256_shuffle_epi8(
      a.v, _mm256_setr_epi8(b, z, z, z, b4, z, z, z, b8, z, z, z, b12, z, z, z, b, z, z, z, b4, z,
                            z, z, b8, z, z, z, b12, z, z, z))};
}
inline I Gather(const int32_t* base, I index, M mask) {
  return {_mm256_mask_i32gather_epi32(_mm256_setzero_si256(), base, index.v,
                                      _mm256_castps_si256(mask.v), 4)};
}
inline I GatherWords(const uint8_t* bytes, I index, M mask) {
  return {_mm256_mask_i32gather_epi32(_mm256_setzero_si256(), reinterpret_cast<const int*>(bytes),
                                      index.v, _mm256_castps_si256(mask.v), 4)};
}
inline bool AllEqual(I a) { return Bits(a == SetI(First(a))) == (1 << kLanes) - 1; }

}  // namespace avx2
APERTURE_LANES8_AVX2_END

// Whether this processor runs the avx2 back end.
inline bool HasAvx2() { return __builtin_cpu_supports("avx2"); }
#else
inline bool HasAvx2() { return false; }
#endif

}  // namespace aperture::lanes8
