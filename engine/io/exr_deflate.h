// OpenEXR's zip and zips compression done by libdeflate instead of zlib: the same stream format
// (zlib, after OpenEXR's byte split and delta predictor), about twice as fast at a given level.
// OpenEXR 3.2 made the same switch; the 3.1 core of Debian bookworm still calls zlib, so the
// encoder installs this as the pipeline's compress_fn.
#pragma once

#include <OpenEXR/openexr.h>

namespace aperture {

// An exr_encode_pipeline_t compress_fn for EXR_COMPRESSION_ZIP / ZIPS. The pipeline's
// `encoding_user_data` must point at the int zlib level (1..9). The compressed bytes live in
// thread-local storage until the same thread compresses its next chunk; a chunk that does not
// shrink is stored raw, as the EXR format allows.
exr_result_t DeflateExrChunk(exr_encode_pipeline_t* encode);

}  // namespace aperture
