// The trilinear batch kernels give the pyramid's own per-sample floats, bit for bit: on a
// non-square noise texture, over footprints from magnified (level 0) through whole levels (a
// blend weight of exactly 0) to beyond the coarsest level, and batch lengths that leave tails.
#include "texture/trilinear_kernels.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "testing/random_image.h"

namespace aperture {
namespace {

TEST(TrilinearKernels, EveryKernelEqualsThePyramid) {
  const MipPyramid pyramid(RandomImage(64, 16, 3));
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> coord(0, 1);
  std::uniform_real_distribution<float> log_scale(-9, 2), sign(-1, 1), unit(0, 1);
  std::uniform_int_distribution<int> count_of(0, FootprintBatch::kMax), whole_level(0, 8);
  const std::vector<std::pair<const char*, TrilinearBatchFn>> kernels = {
      {"avx2", TrilinearBatchAvx2()}, {"best", BestTrilinearBatch()}};
  int checked = 0, blends = 0;
  for (const auto& [name, kernel] : kernels) {
    if (kernel == nullptr) continue;  // not in this build or not on this processor
    SCOPED_TRACE(name);
    for (int trial = 0; trial < 300; ++trial) {
      FootprintBatch batch;
      batch.count = count_of(rng);
      for (int i = 0; i < batch.count; ++i) {
        TextureFootprint f;
        f.u = coord(rng), f.v = coord(rng);
        if (i % 5 == 0) {
          // A footprint exactly 2^k texels long: level k with a blend weight of 0.
          f.dudx = std::ldexp(1.0f, whole_level(rng)) / 64;
          f.dvdx = 0, f.dudy = 0, f.dvdy = 0;
        } else {
          const float scale = std::exp2(log_scale(rng));
          f.dudx = scale * sign(rng), f.dvdx = scale * sign(rng) * unit(rng);
          f.dudy = scale * sign(rng) * unit(rng), f.dvdy = scale * sign(rng);
        }
        batch.Set(i, f);
      }
      std::vector<Rgba> expected(batch.count), got(batch.count);
      TrilinearBatchPortable(pyramid, batch, expected.data());
      kernel(pyramid, batch, got.data());
      for (int i = 0; i < batch.count; ++i) {
        ASSERT_EQ(std::memcmp(&expected[i], &got[i], sizeof(Rgba)), 0)
            << "sample " << i << " of " << batch.count << ": (" << expected[i].r << ", "
            << expected[i].g << ") against (" << got[i].r << ", " << got[i].g << ")";
        const Rgba level0 = pyramid.Bilinear(0, batch.u[i], batch.v[i]);
        blends += !(expected[i] == level0);
      }
      ++checked;
    }
  }
  EXPECT_GT(checked, 0);
  EXPECT_GT(blends, 1000);  // most samples are filtered from coarser levels, not level 0
  EXPECT_STRNE(BestTrilinearBatchName(), "");
}

// The portable kernel is the pyramid's Trilinear, sample by sample.
TEST(TrilinearKernels, PortableIsTheSampler) {
  const MipPyramid pyramid(RandomImage(32, 32, 4));
  FootprintBatch batch;
  batch.count = 3;
  batch.Set(0, {0.25, 0.75, 0.001f, 0, 0, 0.001f});
  batch.Set(1, {0.5, 0.5, 0.3f, 0.1f, -0.1f, 0.2f});
  batch.Set(2, {0.9, 0.1, 40, 0, 0, 40});
  Rgba out[3];
  TrilinearBatchPortable(pyramid, batch, out);
  for (int i = 0; i < 3; ++i) EXPECT_EQ(out[i], pyramid.Trilinear(batch.At(i))) << i;
  // Beyond the coarsest level: the 1x1 level's single texel, the texture's mean.
  EXPECT_EQ(out[2], pyramid.level(pyramid.levels() - 1).at(0, 0));
}

}  // namespace
}  // namespace aperture
