// The trilinear filter (MipPyramid::Trilinear) over a batch of footprints, as kernels: the
// portable one is the pyramid's own per-sample code in a loop; AVX2 (chosen at run time when the
// processor has it) computes the levels, blend weights and texel addresses of four samples at a
// time and blends each sample's eight texels as vectors of RGBA. Both give the same floats: the
// same operations in the same order, no fused multiply-add (tests/texture/
// trilinear_kernels_test.cc checks it bit for bit).
#pragma once

#include "texture/footprint_batch.h"
#include "texture/mip_pyramid.h"

namespace aperture {

using TrilinearBatchFn = void (*)(const MipPyramid& pyramid, const FootprintBatch& in, Rgba* out);

void TrilinearBatchPortable(const MipPyramid& pyramid, const FootprintBatch& in, Rgba* out);
// Null when the build or the processor lacks AVX2.
TrilinearBatchFn TrilinearBatchAvx2();
// The fastest this processor runs, and its name.
TrilinearBatchFn BestTrilinearBatch();
const char* BestTrilinearBatchName();

}  // namespace aperture
