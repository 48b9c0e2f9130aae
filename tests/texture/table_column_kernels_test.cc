// The table build's column kernels give the same floats as the portable one, bit for bit, on
// random texels, weights and run lengths (odd ones too: AVX2 takes lines two at a time), with b
// apart from a and b one line past a.
#include "texture/table_column_kernels.h"

#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <vector>

namespace aperture {
namespace {

TEST(TableColumnKernels, EveryKernelEqualsThePortableOne) {
  std::mt19937 rng(5);
  std::uniform_int_distribution<int> texel(0, 65535), count_of(0, 37);
  std::uniform_real_distribution<float> weight(0, 1), start(0, 1e6f);
  std::vector<std::pair<const char*, AddColumnFn>> kernels = {
      {"sse4.1", AddColumnSse41()}, {"avx2", AddColumnAvx2()}, {"best", BestAddColumn()}};
  int checked = 0;
  for (const auto& [name, kernel] : kernels) {
    if (kernel == nullptr) continue;  // not in this build or not on this processor
    SCOPED_TRACE(name);
    for (int trial = 0; trial < 400; ++trial) {
      const int count = count_of(rng);
      // Odd trials: b is a one line on (the L = 1 lines of a build), which AVX2 reads once.
      const bool consecutive = trial % 2 == 1;
      std::vector<PackedTexel> lines(2 * count + 1);
      for (PackedTexel& t : lines)
        for (uint16_t& c : t) c = static_cast<uint16_t>(texel(rng));
      const PackedTexel* a = lines.data();
      const PackedTexel* b = consecutive ? a + 1 : a + count + 1;
      std::vector<float> expected(4 * count);
      for (float& v : expected) v = start(rng);
      std::vector<float> got = expected;
      const float w = weight(rng);
      AddColumnPortable(expected.data(), a, b, count, w);
      kernel(got.data(), a, b, count, w);
      ASSERT_EQ(std::memcmp(expected.data(), got.data(), expected.size() * sizeof(float)), 0)
          << "count " << count << (consecutive ? ", consecutive lines" : "");
      ++checked;
    }
  }
  EXPECT_GT(checked, 0);
  EXPECT_STRNE(BestAddColumnName(), "");
}

}  // namespace
}  // namespace aperture
