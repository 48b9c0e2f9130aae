// OpenEXR output: RGBA half (default) or float, selectable compression, metadata; to a file or to
// bytes in memory. Encoded by OpenEXR's core library with blocks of scanlines compressed in
// parallel (exr_chunk_encoder.h); dwaa and dwab through OpenImageIO (OpenEXR's C++ library).
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "absl/status/statusor.h"
#include "base/image.h"
#include "io/exr_header.h"

namespace aperture {

enum class ExrCompression { kNone, kRle, kZips, kZip, kPiz, kDwaa, kB44, kB44a, kDwab };
enum class ExrPixelType { kHalf, kFloat };

const char* ExrCompressionName(ExrCompression c);

// Whether the compression encodes half channels only: B44 and B44A leave float channels
// uncompressed, so a float frame asked of them is refused rather than sent at full size.
bool CompressesHalfOnly(ExrCompression c);

struct ExrOptions {
  ExrPixelType pixel_type = ExrPixelType::kHalf;
  ExrCompression compression = ExrCompression::kZip;
  // zlib level of zip and zips (1 fastest .. 9 smallest). 4 is OpenEXR's own default from 3.2 on:
  // with libdeflate, level 6 takes 1.4x its time for a file 4 % smaller (docs/BENCHMARKS.md).
  int zip_level = 4;
  // Blocks of scanlines are compressed in parallel with oneTBB: > 0 in a task arena of that many
  // threads, 0 in the calling thread's arena (a server encodes inside its render arena, so encode
  // and render share the cores instead of oversubscribing them). dwaa and dwab, which OpenEXR
  // 3.1's core library cannot write, go through OpenImageIO on the calling thread.
  int threads = 0;
  ExrMetadata metadata;  // the header, and where the image lies in its frame
};

absl::Status WriteExrFile(const Image& image, const ExrOptions& options, const std::string& path);
// The file's bytes, in a string so that a protobuf message can take them without a copy.
absl::StatusOr<std::string> EncodeExr(const Image& image, const ExrOptions& options);

// An 8-bit sRGB PNG for people to look at (linear values clamped to [0, 1]).
absl::Status WritePngPreview(const Image& image, const std::string& path);

}  // namespace aperture
