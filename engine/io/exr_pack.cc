#include "io/exr_pack.h"

#include <OpenEXR/openexr.h>

#include <cstdint>
#include <cstring>

#if defined(__x86_64__) && defined(__GNUC__)
#include <cpuid.h>
#include <immintrin.h>
#define APERTURE_HAVE_F16C_KERNEL 1
#endif

namespace aperture {
namespace {

#if defined(APERTURE_HAVE_F16C_KERNEL)

// One scanline: `pixels` interleaved RGBA floats to the four planes out[0..3] (R, G, B, A), each
// `width` values of half (2 bytes) or float (4 bytes).
__attribute__((target("avx2,f16c"))) void PackLine(const float* pixels, int width, bool half,
                                                   uint8_t* const out[4]) {
  int x = 0;
  if (half) {
    // Per 8 pixels: four registers of two pixels each, converted to 8 halves (R0 G0 B0 A0 R1 G1
    // B1 A1); a byte shuffle pairs the channels (R0 R1 G0 G1 B0 B1 A0 A1) and a 4 x 4 transpose
    // of the 32-bit pairs gathers each channel's eight values.
    const __m128i pair = _mm_setr_epi8(0, 1, 8, 9, 2, 3, 10, 11, 4, 5, 12, 13, 6, 7, 14, 15);
    for (; x + 8 <= width; x += 8) {
      __m128 v[4];
      for (int k = 0; k < 4; ++k) {
        const __m256 two = _mm256_loadu_ps(pixels + 4 * x + 8 * k);
        const __m128i h = _mm256_cvtps_ph(two, _MM_FROUND_TO_NEAREST_INT | _MM_FROUND_NO_EXC);
        v[k] = _mm_castsi128_ps(_mm_shuffle_epi8(h, pair));
      }
      _MM_TRANSPOSE4_PS(v[0], v[1], v[2], v[3]);
      for (int c = 0; c < 4; ++c)
        _mm_storeu_si128(reinterpret_cast<__m128i*>(out[c] + 2 * x), _mm_castps_si128(v[c]));
    }
    for (; x < width; ++x)
      for (int c = 0; c < 4; ++c) {
        const __m128i one = _mm_cvtps_ph(_mm_set_ss(pixels[4 * x + c]),
                                         _MM_FROUND_TO_NEAREST_INT | _MM_FROUND_NO_EXC);
        const uint16_t h = static_cast<uint16_t>(_mm_extract_epi16(one, 0));
        std::memcpy(out[c] + 2 * x, &h, 2);
      }
    return;
  }
  for (; x + 4 <= width; x += 4) {
    __m128 v[4];
    for (int k = 0; k < 4; ++k) v[k] = _mm_loadu_ps(pixels + 4 * (x + k));
    _MM_TRANSPOSE4_PS(v[0], v[1], v[2], v[3]);
    for (int c = 0; c < 4; ++c) _mm_storeu_ps(reinterpret_cast<float*>(out[c] + 4 * x), v[c]);
  }
  for (; x < width; ++x)
    for (int c = 0; c < 4; ++c) std::memcpy(out[c] + 4 * x, pixels + 4 * x + c, 4);
}

exr_result_t PackRgba(exr_encode_pipeline_t* encode) {
  // The setup this packing is for (io/exr_chunk_encoder's PointAtRows): four channels, float
  // values 16 bytes apart, R's pointer the pixel's start.
  if (encode->channel_count != 4) return EXR_ERR_INVALID_ARGUMENT;
  const uint8_t* base = nullptr;
  int offset[4];  // the RGBA index of the chunk's channel k
  for (int k = 0; k < 4; ++k) {
    const exr_coding_channel_info_t& ch = encode->channels[k];
    if (ch.user_data_type != EXR_PIXEL_FLOAT || ch.user_pixel_stride != 16 || ch.x_samples != 1 ||
        ch.y_samples != 1)
      return EXR_ERR_INVALID_ARGUMENT;
    switch (ch.channel_name[0]) {
      case 'R':
        offset[k] = 0;
        break;
      case 'G':
        offset[k] = 1;
        break;
      case 'B':
        offset[k] = 2;
        break;
      case 'A':
        offset[k] = 3;
        break;
      default:
        return EXR_ERR_INVALID_ARGUMENT;
    }
    if (ch.channel_name[1] != '\0') return EXR_ERR_INVALID_ARGUMENT;
    const uint8_t* start = ch.encode_from_ptr - 4 * offset[k];
    if (k > 0 && start != base) return EXR_ERR_INVALID_ARGUMENT;
    base = start;
  }
  const exr_coding_channel_info_t& first = encode->channels[0];
  const int width = first.width, height = first.height;
  const bool half = first.bytes_per_element == 2;
  const int line_stride = first.user_line_stride;
  uint8_t* dst = static_cast<uint8_t*>(encode->packed_buffer);
  const size_t plane = static_cast<size_t>(width) * first.bytes_per_element;
  for (int y = 0; y < height; ++y) {
    uint8_t* out[4];
    for (int k = 0; k < 4; ++k) out[offset[k]] = dst + k * plane;
    PackLine(reinterpret_cast<const float*>(base + static_cast<size_t>(y) * line_stride), width,
             half, out);
    dst += 4 * plane;
  }
  encode->packed_bytes = static_cast<uint64_t>(dst - static_cast<uint8_t*>(encode->packed_buffer));
  return EXR_ERR_SUCCESS;
}

#endif

}  // namespace

ExrPackFn FastRgbaPack() {
#if defined(APERTURE_HAVE_F16C_KERNEL)
  // F16C is CPUID leaf 1, ECX bit 29 (clang's __builtin_cpu_supports does not name it); AVX2
  // implies the operating system keeps the AVX state the conversion uses.
  unsigned eax = 0, ebx = 0, ecx = 0, edx = 0;
  const bool f16c = __get_cpuid(1, &eax, &ebx, &ecx, &edx) && (ecx & (1u << 29)) != 0;
  if (__builtin_cpu_supports("avx2") && f16c) return PackRgba;
#endif
  return nullptr;
}

}  // namespace aperture
