// OpenEXR output through OpenImageIO: RGBA half (default) or float, selectable compression,
// metadata; to a file or to bytes in memory (single-part, which OpenImageIO 2.4 writes correctly).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "texture/image.h"

namespace aperture {

enum class ExrCompression { kNone, kRle, kZips, kZip, kPiz, kDwaa };
enum class ExrPixelType { kHalf, kFloat };

const char* ExrCompressionName(ExrCompression c);
absl::StatusOr<ExrCompression> ParseExrCompression(const std::string& name);

struct ExrMetadata {
  std::string scene_name;
  std::string camera;  // "X,Y,Z,YAW,PITCH,ROLL fov=..."
  double render_ms = 0;
  std::vector<std::pair<std::string, std::string>> extra;  // more string attributes
};

struct ExrOptions {
  ExrPixelType pixel_type = ExrPixelType::kHalf;
  ExrCompression compression = ExrCompression::kZip;
  // OpenEXR's own thread pool for compression, a process-wide setting of OpenImageIO
  // ("exr_threads"): N pool threads, 0 all cores, -1 no pool (the caller compresses). The default
  // is -1 because a process encoding several frames at once must not share the pool: a server's two
  // concurrent frames waiting on OpenEXR 3.1's one global pool left a request waiting forever in
  // OutputFile::writePixels once in a 5-minute load run. Only a lone encoder (aperture-render)
  // should ask for a pool.
  int threads = -1;
  ExrMetadata metadata;
};

absl::Status WriteExrFile(const Image& image, const ExrOptions& options, const std::string& path);
absl::StatusOr<std::vector<uint8_t>> EncodeExr(const Image& image, const ExrOptions& options);

// An 8-bit sRGB PNG for people to look at (linear values clamped to [0, 1]).
absl::Status WritePngPreview(const Image& image, const std::string& path);

}  // namespace aperture
