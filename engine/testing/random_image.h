// Noise images for the tests and benchmarks: every channel uniform in [0, 1) from a seeded
// generator, so that a test's texture is the same on every run and machine.
#pragma once

#include <cstdint>

#include "base/image.h"

namespace aperture {

// Alpha is 1 unless `random_alpha`.
Image RandomImage(int width, int height, uint32_t seed, bool random_alpha = false);

}  // namespace aperture
