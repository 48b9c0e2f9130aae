#include "render/footprint_kernels.h"

#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#define APERTURE_HAVE_AVX2_KERNEL 1
#endif

namespace aperture {

namespace {

// Pixels begin..run.count of the run, one at a time: the portable kernel, and the tail of a
// vector kernel.
void RowFootprintsFrom(int begin, const ScreenPolygon& p, double min_inv_depth, double aperture,
                       const RowRun& run, FootprintBatch& out, double* inv_depth) {
  for (int i = begin; i < run.count; ++i) {
    const double x = run.x0 + (run.first + i);
    inv_depth[i] = InvDepthAt(p, min_inv_depth, x, run.y);
    out.Set(i, FootprintAt(p, aperture, inv_depth[i], x, run.y));
  }
  out.count = run.count;
}

#if defined(APERTURE_HAVE_AVX2_KERNEL)

__attribute__((target("avx2"))) void RowFootprintsAvx2Kernel(const ScreenPolygon& p,
                                                             double min_inv_depth, double aperture,
                                                             const RowRun& run, FootprintBatch& out,
                                                             double* inv_depth) {
  const ScreenLinear &z = p.inv_depth, &un = p.u_num, &vn = p.v_num;
  // ScreenLinear::At(x, y) = (a x + b y) + c; b y is the same for the whole row.
  const __m256d z_a = _mm256_set1_pd(z.a), z_by = _mm256_set1_pd(z.b * run.y);
  const __m256d z_c = _mm256_set1_pd(z.c), z_b = _mm256_set1_pd(z.b);
  const __m256d u_a = _mm256_set1_pd(un.a), u_by = _mm256_set1_pd(un.b * run.y);
  const __m256d u_c = _mm256_set1_pd(un.c), u_b = _mm256_set1_pd(un.b);
  const __m256d v_a = _mm256_set1_pd(vn.a), v_by = _mm256_set1_pd(vn.b * run.y);
  const __m256d v_c = _mm256_set1_pd(vn.c), v_b = _mm256_set1_pd(vn.b);
  const __m256d floor_w = _mm256_set1_pd(min_inv_depth), a = _mm256_set1_pd(aperture);
  const __m256d one = _mm256_set1_pd(1.0), x0 = _mm256_set1_pd(run.x0);
  const __m256d lanes = _mm256_set_pd(3, 2, 1, 0);
  int i = 0;
  for (; i + 4 <= run.count; i += 4) {
    const __m256d x =
        _mm256_add_pd(x0, _mm256_add_pd(_mm256_set1_pd(static_cast<double>(run.first + i)), lanes));
    // std::max(At, min_inv_depth): max_pd(m, at) is m > at ? m : at.
    const __m256d w =
        _mm256_max_pd(floor_w, _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(z_a, x), z_by), z_c));
    const __m256d inv_w = _mm256_div_pd(one, w);
    const __m256d u =
        _mm256_mul_pd(_mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(u_a, x), u_by), u_c), inv_w);
    const __m256d v =
        _mm256_mul_pd(_mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(v_a, x), v_by), v_c), inv_w);
    const __m256d s = _mm256_mul_pd(a, inv_w);
    _mm256_store_pd(inv_depth + i, w);
    _mm256_store_pd(out.u + i, _mm256_sub_pd(u, _mm256_floor_pd(u)));
    _mm256_store_pd(out.v + i, _mm256_sub_pd(v, _mm256_floor_pd(v)));
    _mm_store_ps(out.dudx + i,
                 _mm256_cvtpd_ps(_mm256_mul_pd(_mm256_sub_pd(u_a, _mm256_mul_pd(z_a, u)), s)));
    _mm_store_ps(out.dvdx + i,
                 _mm256_cvtpd_ps(_mm256_mul_pd(_mm256_sub_pd(v_a, _mm256_mul_pd(z_a, v)), s)));
    _mm_store_ps(out.dudy + i,
                 _mm256_cvtpd_ps(_mm256_mul_pd(_mm256_sub_pd(u_b, _mm256_mul_pd(z_b, u)), s)));
    _mm_store_ps(out.dvdy + i,
                 _mm256_cvtpd_ps(_mm256_mul_pd(_mm256_sub_pd(v_b, _mm256_mul_pd(z_b, v)), s)));
  }
  // GCC emits no vzeroupper here (the scalar tail is inlined), and the upper halves left dirty
  // made every legacy-SSE instruction after the kernel stall: glibc's exp() in the fog took 30 %
  // of a frame whose sampler is not AVX (the airport's packed map).
  _mm256_zeroupper();
  RowFootprintsFrom(i, p, min_inv_depth, aperture, run, out, inv_depth);
}

#endif

}  // namespace

void RowFootprintsPortable(const ScreenPolygon& p, double min_inv_depth, double aperture,
                           const RowRun& run, FootprintBatch& out, double* inv_depth) {
  RowFootprintsFrom(0, p, min_inv_depth, aperture, run, out, inv_depth);
}

RowFootprintsFn RowFootprintsAvx2() {
#if defined(APERTURE_HAVE_AVX2_KERNEL)
  if (__builtin_cpu_supports("avx2")) return RowFootprintsAvx2Kernel;
#endif
  return nullptr;
}

RowFootprintsFn BestRowFootprints() {
  if (RowFootprintsFn f = RowFootprintsAvx2()) return f;
  return RowFootprintsPortable;
}

const char* BestRowFootprintsName() { return RowFootprintsAvx2() ? "avx2" : "portable"; }

}  // namespace aperture
