// Packing of the EXR encoder's chunks from the frame's interleaved float RGBA rows: each scanline
// of the chunk as one plane per channel, in the header's channel order, as half or float. The
// core library's own packing converts one value at a time; this one converts eight at a time by
// the F16C instructions (chosen at run time) and transposes them into the planes, with the same
// rounding (to nearest even, as Imath::half): the same bytes (tests/io/exr_pack_test.cc).
#pragma once

#include <cstdint>

// OpenEXR core's encode pipeline (OpenEXR/openexr_encode.h), declared here so that this header
// does not bring the core's C headers to its users.
struct _exr_encode_pipeline;

namespace aperture {

// exr_result_t (*)(exr_encode_pipeline_t*), the type of the pipeline's convert_and_pack_fn.
using ExrPackFn = int32_t (*)(_exr_encode_pipeline* encode);

// The packing for chunks whose channels are R, G, B and A (any order) read from one array of
// 16-byte float RGBA pixels, the layout io/exr_chunk_encoder sets up; null when the processor
// lacks AVX2 and F16C (the core library's own then packs).
ExrPackFn FastRgbaPack();

}  // namespace aperture
