// The row footprint kernels give the per-sample footprints bit for bit: random planes seen in
// perspective (depth increasing along the row or across it, texture coordinates far from zero),
// pixel centres where the depth clamp at the farthest vertex takes over, and runs whose length
// leaves tails.
#include "render/footprint_kernels.h"

#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <vector>

namespace aperture {
namespace {

TEST(FootprintKernels, EveryKernelEqualsThePerSampleFootprint) {
  std::mt19937 rng(21);
  std::uniform_real_distribution<double> coefficient(-1, 1), offset(-2000, 2000), pixel(0, 1920);
  std::uniform_int_distribution<int> count_of(0, FootprintBatch::kMax), first_of(0, 200);
  const std::vector<std::pair<const char*, RowFootprintsFn>> kernels = {
      {"avx2", RowFootprintsAvx2()}, {"best", BestRowFootprints()}};
  int checked = 0, clamped = 0;
  for (const auto& [name, kernel] : kernels) {
    if (kernel == nullptr) continue;  // not in this build or not on this processor
    SCOPED_TRACE(name);
    for (int trial = 0; trial < 400; ++trial) {
      ScreenPolygon p;
      p.inv_depth = {1e-4 * coefficient(rng), 1e-3 * coefficient(rng), 0.5 + coefficient(rng)};
      p.u_num = {0.01 * coefficient(rng), 0.01 * coefficient(rng), offset(rng)};
      p.v_num = {0.01 * coefficient(rng), 0.01 * coefficient(rng), offset(rng)};
      const double min_inv_depth = 0.3 + 0.2 * coefficient(rng);
      const double aperture = trial % 2 == 0 ? 1.0 : 2.0;
      // Pixel centres (x.5) on even trials, arbitrary starts on odd ones.
      const double x0 = trial % 2 == 0 ? std::floor(pixel(rng)) + 0.5 : pixel(rng);
      const RowRun run{x0, std::floor(pixel(rng) / 2) + 0.5, first_of(rng), count_of(rng)};
      FootprintBatch expected, got;
      double expected_w[FootprintBatch::kMax], got_w[FootprintBatch::kMax];
      RowFootprintsPortable(p, min_inv_depth, aperture, run, expected, expected_w);
      kernel(p, min_inv_depth, aperture, run, got, got_w);
      ASSERT_EQ(got.count, run.count);
      for (int i = 0; i < run.count; ++i) {
        const TextureFootprint e = expected.At(i), g = got.At(i);
        ASSERT_EQ(std::memcmp(&expected_w[i], &got_w[i], sizeof(double)), 0) << i;
        ASSERT_TRUE(std::memcmp(&e.u, &g.u, sizeof(double)) == 0 &&
                    std::memcmp(&e.v, &g.v, sizeof(double)) == 0 && e.dudx == g.dudx &&
                    e.dvdx == g.dvdx && e.dudy == g.dudy && e.dvdy == g.dvdy)
            << "pixel " << i << " of " << run.count << ": u " << e.u << " against " << g.u;
        clamped += expected_w[i] == min_inv_depth;
        // And the portable kernel is the per-sample function.
        const double x = run.x0 + (run.first + i);
        const double w = InvDepthAt(p, min_inv_depth, x, run.y);
        ASSERT_EQ(w, expected_w[i]);
        ASSERT_EQ(FootprintAt(p, aperture, w, x, run.y).u, e.u);
      }
      ++checked;
    }
  }
  EXPECT_GT(checked, 0);
  EXPECT_GT(clamped, 100);  // the clamp at the farthest vertex was exercised
  EXPECT_STRNE(BestRowFootprintsName(), "");
}

}  // namespace
}  // namespace aperture
