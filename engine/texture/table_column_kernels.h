// The inner loop of seed 000's table build (prefiltered_table_builder.cc): one column of the
// running sums along the sheared lines, for a run of consecutive lines. Three versions that give
// the same floats (the same operations in the same order, no fused multiply-add): portable,
// SSE4.1 (the build's baseline) and AVX2, chosen at run time when the processor has it.
#pragma once

#include <array>
#include <cstdint>

namespace aperture {

// A texel of the minor-axis pass: RGBA in 16-bit fixed point (1 = 65535).
using PackedTexel = std::array<uint16_t, 4>;

// acc[4 l + i] += a[l][i] + (b[l][i] - a[l][i]) w for l < count, i < 4 (in float).
using AddColumnFn = void (*)(float* acc, const PackedTexel* a, const PackedTexel* b, int count,
                             float w);

void AddColumnPortable(float* acc, const PackedTexel* a, const PackedTexel* b, int count, float w);
// Null when the build or the processor lacks the instructions.
AddColumnFn AddColumnSse41();
AddColumnFn AddColumnAvx2();
// The fastest this processor runs.
AddColumnFn BestAddColumn();
const char* BestAddColumnName();

}  // namespace aperture
