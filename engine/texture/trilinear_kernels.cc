#include "texture/trilinear_kernels.h"

#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#define APERTURE_HAVE_AVX2_KERNEL 1
#endif

namespace aperture {

void TrilinearBatchPortable(const MipPyramid& pyramid, const FootprintBatch& in, Rgba* out) {
  for (int i = 0; i < in.count; ++i) out[i] = pyramid.Trilinear(in.At(i));
}

namespace {

#if defined(APERTURE_HAVE_AVX2_KERNEL)

// Four samples' bilinear taps on their levels (MipPyramid::Bilinear): the texel index (in the
// level) of each corner and the weights along x and y.
struct Taps {
  alignas(16) int level[4];
  alignas(16) int x0[4], x1[4], row0[4], row1[4];
  alignas(16) float fx[4], fy[4];
};

// MipPyramid::FastLog2 on four floats.
__attribute__((target("avx2"))) inline __m128 FastLog2(__m128 x) {
  const __m128i bits = _mm_castps_si128(x);
  const __m128 exponent = _mm_cvtepi32_ps(_mm_sub_epi32(
      _mm_and_si128(_mm_srli_epi32(bits, 23), _mm_set1_epi32(255)), _mm_set1_epi32(127)));
  const __m128 m = _mm_castsi128_ps(
      _mm_or_si128(_mm_and_si128(bits, _mm_set1_epi32(0x7fffff)), _mm_set1_epi32(0x3f800000)));
  const __m128 poly =
      _mm_mul_ps(_mm_add_ps(_mm_mul_ps(_mm_set1_ps(-0.34484843f), m), _mm_set1_ps(2.02466578f)), m);
  return _mm_sub_ps(_mm_add_ps(exponent, poly), _mm_set1_ps(0.67487759f));
}

// The taps of four samples at (u, v) on levels `level` (a power-of-two level is
// max(1, base >> level) texels wide).
__attribute__((target("avx2"))) inline void ComputeTaps(__m256d u, __m256d v, __m128i level,
                                                        __m128i base_width, __m128i base_height,
                                                        Taps& taps) {
  const __m128i one = _mm_set1_epi32(1);
  const __m128i w = _mm_max_epi32(_mm_srlv_epi32(base_width, level), one);
  const __m128i h = _mm_max_epi32(_mm_srlv_epi32(base_height, level), one);
  const __m128 half = _mm_set1_ps(0.5f);
  // x = float(u w) - 0.5, its floor and fraction; likewise y.
  const __m128 x = _mm_sub_ps(_mm256_cvtpd_ps(_mm256_mul_pd(u, _mm256_cvtepi32_pd(w))), half);
  const __m128 y = _mm_sub_ps(_mm256_cvtpd_ps(_mm256_mul_pd(v, _mm256_cvtepi32_pd(h))), half);
  const __m128 fx0 = _mm_floor_ps(x), fy0 = _mm_floor_ps(y);
  const __m128i wmask = _mm_sub_epi32(w, one), hmask = _mm_sub_epi32(h, one);
  const __m128i x0 = _mm_and_si128(_mm_cvttps_epi32(fx0), wmask);
  const __m128i y0 = _mm_and_si128(_mm_cvttps_epi32(fy0), hmask);
  const __m128i x1 = _mm_and_si128(_mm_add_epi32(x0, one), wmask);
  const __m128i y1 = _mm_and_si128(_mm_add_epi32(y0, one), hmask);
  _mm_store_si128(reinterpret_cast<__m128i*>(taps.level), level);
  _mm_store_si128(reinterpret_cast<__m128i*>(taps.x0), x0);
  _mm_store_si128(reinterpret_cast<__m128i*>(taps.x1), x1);
  _mm_store_si128(reinterpret_cast<__m128i*>(taps.row0), _mm_mullo_epi32(y0, w));
  _mm_store_si128(reinterpret_cast<__m128i*>(taps.row1), _mm_mullo_epi32(y1, w));
  _mm_store_ps(taps.fx, _mm_sub_ps(x, fx0));
  _mm_store_ps(taps.fy, _mm_sub_ps(y, fy0));
}

// MipPyramid::Bilinear of sample k from its taps, the four channels at once.
__attribute__((target("avx2"))) inline __m128 Bilinear(const Rgba* const* levels, const Taps& taps,
                                                       int k) {
  const float* texels = &levels[taps.level[k]]->r;
  const __m128 t00 = _mm_loadu_ps(texels + 4 * (taps.row0[k] + taps.x0[k]));
  const __m128 t01 = _mm_loadu_ps(texels + 4 * (taps.row0[k] + taps.x1[k]));
  const __m128 t10 = _mm_loadu_ps(texels + 4 * (taps.row1[k] + taps.x0[k]));
  const __m128 t11 = _mm_loadu_ps(texels + 4 * (taps.row1[k] + taps.x1[k]));
  const __m128 fx = _mm_set1_ps(taps.fx[k]), fy = _mm_set1_ps(taps.fy[k]);
  const __m128 one = _mm_set1_ps(1.0f);
  const __m128 gx = _mm_sub_ps(one, fx), gy = _mm_sub_ps(one, fy);
  const __m128 row0 = _mm_add_ps(_mm_mul_ps(t00, gx), _mm_mul_ps(t01, fx));
  const __m128 row1 = _mm_add_ps(_mm_mul_ps(t10, gx), _mm_mul_ps(t11, fx));
  return _mm_add_ps(_mm_mul_ps(row0, gy), _mm_mul_ps(row1, fy));
}

// MipPyramid::Trilinear, four samples at a time.
__attribute__((target("avx2"))) void TrilinearBatchAvx2Kernel(const MipPyramid& pyramid,
                                                              const FootprintBatch& in, Rgba* out) {
  const Rgba* levels[64];
  for (int l = 0; l < pyramid.levels(); ++l) levels[l] = pyramid.level(l).texels().data();
  const int top = pyramid.levels() - 1;
  const float width = static_cast<float>(pyramid.level(0).width());
  const float height = static_cast<float>(pyramid.level(0).height());
  const __m128 w = _mm_set1_ps(width), h = _mm_set1_ps(height);
  const __m128i base_width = _mm_set1_epi32(pyramid.level(0).width());
  const __m128i base_height = _mm_set1_epi32(pyramid.level(0).height());
  const __m128i top_v = _mm_set1_epi32(top);
  int i = 0;
  for (; i + 4 <= in.count; i += 4) {
    // The level of detail from the longer footprint axis.
    const __m128 ux = _mm_mul_ps(_mm_load_ps(in.dudx + i), w);
    const __m128 vx = _mm_mul_ps(_mm_load_ps(in.dvdx + i), h);
    const __m128 uy = _mm_mul_ps(_mm_load_ps(in.dudy + i), w);
    const __m128 vy = _mm_mul_ps(_mm_load_ps(in.dvdy + i), h);
    const __m128 along_x = _mm_add_ps(_mm_mul_ps(ux, ux), _mm_mul_ps(vx, vx));
    const __m128 along_y = _mm_add_ps(_mm_mul_ps(uy, uy), _mm_mul_ps(vy, vy));
    const __m128 rho2 = _mm_max_ps(along_y, along_x);  // std::max(along_x, along_y)
    const __m128 lod = _mm_and_ps(_mm_cmpgt_ps(rho2, _mm_set1_ps(1.0f)),
                                  _mm_mul_ps(_mm_set1_ps(0.5f), FastLog2(rho2)));
    const __m128 beyond = _mm_cmpge_ps(lod, _mm_cvtepi32_ps(top_v));  // the coarsest level only
    const __m128i l0 = _mm_cvttps_epi32(lod);
    const __m128 t = _mm_sub_ps(lod, _mm_cvtepi32_ps(l0));
    const __m128i first =
        _mm_castps_si128(_mm_blendv_ps(_mm_castsi128_ps(l0), _mm_castsi128_ps(top_v), beyond));
    const __m128i second = _mm_min_epi32(_mm_add_epi32(first, _mm_set1_epi32(1)), top_v);
    const int one_level = _mm_movemask_ps(_mm_or_ps(beyond, _mm_cmpeq_ps(t, _mm_setzero_ps())));
    alignas(16) float blend[4];
    _mm_store_ps(blend, t);

    const __m256d u = _mm256_load_pd(in.u + i), v = _mm256_load_pd(in.v + i);
    Taps near, far;
    ComputeTaps(u, v, first, base_width, base_height, near);
    // Magnified or whole-level samples read one level: the second's taps are not needed.
    if (one_level != 0xf) ComputeTaps(u, v, second, base_width, base_height, far);
    for (int k = 0; k < 4; ++k) {
      __m128 colour = Bilinear(levels, near, k);
      if ((one_level >> k & 1) == 0) {
        const __m128 tk = _mm_set1_ps(blend[k]);
        colour = _mm_add_ps(_mm_mul_ps(colour, _mm_sub_ps(_mm_set1_ps(1.0f), tk)),
                            _mm_mul_ps(Bilinear(levels, far, k), tk));
      }
      _mm_storeu_ps(&out[i + k].r, colour);
    }
  }
  for (; i < in.count; ++i) out[i] = pyramid.Trilinear(in.At(i));
}

#endif

}  // namespace

TrilinearBatchFn TrilinearBatchAvx2() {
#if defined(APERTURE_HAVE_AVX2_KERNEL)
  if (__builtin_cpu_supports("avx2")) return TrilinearBatchAvx2Kernel;
#endif
  return nullptr;
}

TrilinearBatchFn BestTrilinearBatch() {
  if (TrilinearBatchFn f = TrilinearBatchAvx2()) return f;
  return TrilinearBatchPortable;
}

const char* BestTrilinearBatchName() { return TrilinearBatchAvx2() ? "avx2" : "portable"; }

}  // namespace aperture
