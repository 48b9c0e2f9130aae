#include "io/exr_deflate.h"

#include <libdeflate.h>

#include <cstdint>
#include <vector>

namespace aperture {
namespace {

struct DeflateScratch {
  libdeflate_compressor* compressor = nullptr;
  int level = -1;
  std::vector<uint8_t> predicted, compressed;
  ~DeflateScratch() {
    if (compressor != nullptr) libdeflate_free_compressor(compressor);
  }
  bool SetLevel(int wanted) {
    if (compressor != nullptr && level == wanted) return true;
    if (compressor != nullptr) libdeflate_free_compressor(compressor);
    compressor = libdeflate_alloc_compressor(wanted);
    level = wanted;
    return compressor != nullptr;
  }
};

// OpenEXR's zip preprocessing (ImfZip.cpp, internal_zip.c): the even bytes, then the odd ones
// (the two bytes of a half apart), then each byte as the difference from the one before + 128.
void SplitAndPredict(const uint8_t* in, size_t n, uint8_t* out) {
  uint8_t* even = out;
  uint8_t* odd = out + (n + 1) / 2;
  for (size_t i = 0; i + 1 < n; i += 2) {
    *even++ = in[i];
    *odd++ = in[i + 1];
  }
  if (n % 2 == 1) *even = in[n - 1];
  int previous = out[0];
  for (size_t i = 1; i < n; ++i) {
    const int d = static_cast<int>(out[i]) - previous + (128 + 256);
    previous = out[i];
    out[i] = static_cast<uint8_t>(d);
  }
}

}  // namespace

exr_result_t DeflateExrChunk(exr_encode_pipeline_t* encode) {
  thread_local DeflateScratch scratch;
  const int level = *static_cast<const int*>(encode->encoding_user_data);
  if (!scratch.SetLevel(level)) return EXR_ERR_OUT_OF_MEMORY;
  const size_t n = encode->packed_bytes;
  const auto* packed = static_cast<const uint8_t*>(encode->packed_buffer);
  scratch.predicted.resize(n);
  SplitAndPredict(packed, n, scratch.predicted.data());
  scratch.compressed.resize(libdeflate_zlib_compress_bound(scratch.compressor, n));
  const size_t size =
      libdeflate_zlib_compress(scratch.compressor, scratch.predicted.data(), n,
                               scratch.compressed.data(), scratch.compressed.size());
  // Buffers the pipeline does not own (alloc size 0): it neither frees nor reuses them.
  encode->compressed_alloc_size = 0;
  if (size == 0 || size >= n) {
    encode->compressed_buffer = encode->packed_buffer;
    encode->compressed_bytes = n;
  } else {
    encode->compressed_buffer = scratch.compressed.data();
    encode->compressed_bytes = size;
  }
  return EXR_ERR_SUCCESS;
}

}  // namespace aperture
