#include "texture/table_column_kernels.h"

#if defined(__SSE4_1__)
#include <smmintrin.h>
#endif
#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#define APERTURE_HAVE_AVX2_KERNEL 1
#endif

namespace aperture {

void AddColumnPortable(float* acc, const PackedTexel* a, const PackedTexel* b, int count, float w) {
  for (int l = 0; l < count; ++l)
    for (int i = 0; i < 4; ++i) {
      const float fa = a[l][i], fb = b[l][i];
      acc[4 * l + i] = acc[4 * l + i] + (fa + (fb - fa) * w);
    }
}

namespace {

#if defined(__SSE4_1__)
inline __m128 Load4(const PackedTexel& t) {
  return _mm_cvtepi32_ps(
      _mm_cvtepu16_epi32(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(t.data()))));
}

void AddColumnSse(float* acc, const PackedTexel* a, const PackedTexel* b, int count, float w) {
  const __m128 wv = _mm_set1_ps(w);
  for (int l = 0; l < count; ++l) {
    const __m128 fa = Load4(a[l]), fb = Load4(b[l]);
    const __m128 sum = _mm_loadu_ps(acc + 4 * l);
    _mm_storeu_ps(acc + 4 * l, _mm_add_ps(sum, _mm_add_ps(fa, _mm_mul_ps(_mm_sub_ps(fb, fa), wv))));
  }
}
#endif

#if defined(APERTURE_HAVE_AVX2_KERNEL)
__attribute__((target("avx2"))) inline __m256 LoadTwo(const PackedTexel* t) {
  return _mm256_cvtepi32_ps(
      _mm256_cvtepu16_epi32(_mm_loadu_si128(reinterpret_cast<const __m128i*>(t->data()))));
}

__attribute__((target("avx2"))) inline void AddTwo(float* acc, __m256 fa, __m256 fb, __m256 wv) {
  const __m256 sum = _mm256_loadu_ps(acc);
  _mm256_storeu_ps(acc,
                   _mm256_add_ps(sum, _mm256_add_ps(fa, _mm256_mul_ps(_mm256_sub_ps(fb, fa), wv))));
}

// Two lines per instruction. target("avx2") only: without "fma" the compiler cannot fuse the
// multiply and the add, so each lane computes what the SSE kernel computes.
__attribute__((target("avx2"))) void AddColumnAvx2Kernel(float* acc, const PackedTexel* a,
                                                         const PackedTexel* b, int count, float w) {
  const __m256 wv = _mm256_set1_ps(w);
  int l = 0;
  if (b == a + 1) {
    // b is a one line on (L = 1, the bulk of a table's build): each texel is converted once,
    // and b's pair is the upper half of a's and the lower half of the next pair.
    __m256 fa = LoadTwo(a);
    for (; l + 3 <= count; l += 2) {
      const __m256 next = LoadTwo(a + l + 2);
      AddTwo(acc + 4 * l, fa, _mm256_permute2f128_ps(fa, next, 0x21), wv);
      fa = next;
    }
  }
  for (; l + 2 <= count; l += 2) AddTwo(acc + 4 * l, LoadTwo(a + l), LoadTwo(b + l), wv);
  if (l < count) AddColumnPortable(acc + 4 * l, a + l, b + l, count - l, w);
}
#endif

}  // namespace

AddColumnFn AddColumnSse41() {
#if defined(__SSE4_1__)
  return AddColumnSse;
#else
  return nullptr;
#endif
}

AddColumnFn AddColumnAvx2() {
#if defined(APERTURE_HAVE_AVX2_KERNEL)
  if (__builtin_cpu_supports("avx2")) return AddColumnAvx2Kernel;
#endif
  return nullptr;
}

AddColumnFn BestAddColumn() {
  if (AddColumnFn f = AddColumnAvx2()) return f;
  if (AddColumnFn f = AddColumnSse41()) return f;
  return AddColumnPortable;
}

const char* BestAddColumnName() {
  if (AddColumnAvx2()) return "avx2";
  if (AddColumnSse41()) return "sse4.1";
  return "portable";
}

}  // namespace aperture
