// EXR encoding through OpenEXR's C core (OpenEXRCore), chunk by chunk: blocks of scanlines are
// packed and compressed in parallel by oneTBB and written in file order, the use the core library
// is designed for ("meant to be used by separate threads", openexr_encode.h). No global thread
// pool is involved, so two frames encoding at once in one process cannot wait on each other.
#pragma once

#include <string>

#include "absl/status/status.h"
#include "io/exr_writer.h"

namespace aperture {

// Whether OpenEXR 3.1's core library can write this compression (dwaa and dwab it cannot).
bool CoreEncoderSupports(ExrCompression compression);

// Encodes `image` as a single-part scanline EXR into `bytes` (replaced). Parallel in the calling
// thread's task arena, or in an arena of `options.threads` threads when that is > 0.
absl::Status EncodeExrChunks(const Image& image, const ExrOptions& options, std::string* bytes);

}  // namespace aperture
