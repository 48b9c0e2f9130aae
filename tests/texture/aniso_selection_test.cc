// The seed 000 copy selection's AVX2 build against its portable build: the same readings,
// copies, weights and probes, bit for bit, on footprints of every class.
#include "texture/aniso_selection.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>

#include "testing/random_image.h"
#include "texture/prefiltered_table_builder.h"

namespace aperture {
namespace {

constexpr int kN = 64;

// Derivatives (repeats per pixel) of every class: magnified (the taps, and their fade into the
// readings), thin (the base probes), short (the box probes, in one row or two, and whole groups
// of them), three copies on both axes, near a diagonal (both readings), the frozen region, whole
// periods, zero, tiny, huge, infinite and NaN.
std::vector<std::array<float, 4>> Footprints(int count, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> turn(0, 2 * M_PI), log_len(-4, 24), log_ratio(0, 14),
      unit(0, 1);
  std::vector<std::array<float, 4>> out;
  for (int k = 0; k < count; ++k) {
    double angle = turn(rng);
    if (k % 4 == 0) angle = M_PI / 4 + (unit(rng) - 0.5) * 0.2;  // near the diagonal
    double len = std::exp2(log_len(rng)), thick = len / std::exp2(log_ratio(rng));
    if ((k / 8) % 10 == 3) {
      // Whole groups of short footprints near an axis, read by the box probes alone (half-extents
      // H = 1-4, L = 0.5-1.25 texels: len and thick are twice them).
      angle = (k % 2) * M_PI / 2 + (unit(rng) - 0.5) * 0.2;
      len = 2 + 6 * unit(rng), thick = std::min(len, 1 + 1.5 * unit(rng));
    }
    if ((k / 8) % 10 == 6 && k % 2 == 0) {
      // Nearly round, near a diagonal, half-extents 0.88-1 texel: the magnified taps fading into
      // both readings in the principal axes, of which the first alone is read.
      angle = M_PI / 4 + (unit(rng) - 0.5) * 0.1;
      len = 2 * (0.88 + 0.12 * unit(rng)), thick = len * (0.97 + 0.03 * unit(rng));
    }
    const double c = std::cos(angle), s = std::sin(angle);
    std::array<float, 4> d = {float(len * c / kN), float(len * s / kN), float(-thick * s / kN),
                              float(thick * c / kN)};
    switch ((k / 8) % 10 == 3 ? 0 : k % 23) {
      case 5:
        d = {0, 0, 0, 0};
        break;
      case 7:
        d[1] = NAN;
        break;
      case 11:
        d[2] = INFINITY;
        break;
      case 13:
        d = {1e-25f, 0, 0, 1e-25f};
        break;
      case 17:
        d = {3e30f, 1e-3f, -2e-3f, 5e25f};
        break;
      default:
        break;
    }
    out.push_back(d);
  }
  return out;
}

TEST(AnisoSelection, TheAvx2KernelEqualsThePortableOneBitForBit) {
  auto block = BuildPrefilteredTable(RandomImage(kN, kN, 31));
  ASSERT_TRUE(block.ok()) << block.status();
  auto table = block->View();
  ASSERT_TRUE(table.ok());
  const CopySelector selector(*table);
  if (!selector.has_kernel()) GTEST_SKIP() << "no AVX2 on this processor: one code path only";
  const auto footprints = Footprints(8000, 5);
  int compared = 0, second_readings = 0, probed = 0, magnified = 0, degenerate = 0;
  int boxed = 0, two_rows = 0, whole_box_groups = 0;
  int one_of_two = 0;  // magnified near a diagonal: both readings in the principal axes, one read
  int tapped = 0, faded = 0;  // the magnified taps; between them and the readings
  for (size_t first = 0; first + 8 <= footprints.size(); first += 8) {
    float d[4][8];
    for (int lane = 0; lane < 8; ++lane)
      for (int c = 0; c < 4; ++c) d[c][lane] = footprints[first + lane][c];
    SelectionLanes portable, kernel;
    selector.SelectPortable(d[0], d[1], d[2], d[3], 8, portable);
    selector.Select(d[0], d[1], d[2], d[3], 8, kernel);
    bool whole_box = true;  // every lane read by the box probes alone
    for (int lane = 0; lane < 8; ++lane) {
      for (int r = 0; r < 2; ++r) {
        if (!(portable.reading_weight[r][lane] > 0.0f)) continue;
        whole_box = whole_box && portable.box_probes[r][lane] > 0;
        for (int s = 0; s < SelectionLanes::kSlots; ++s)
          whole_box = whole_box && portable.weight[r][s][lane] == 0.0f;
      }
    }
    whole_box_groups += whole_box;
    for (int lane = 0; lane < 8; ++lane) {
      SCOPED_TRACE(testing::Message() << "footprint " << first + lane);
      bool any = false;
      for (int r = 0; r < 2; ++r) {
        auto bits = [](float x) {
          uint32_t b;
          std::memcpy(&b, &x, 4);
          return b;
        };
        ASSERT_EQ(bits(portable.reading_weight[r][lane]), bits(kernel.reading_weight[r][lane]));
        if (!(portable.reading_weight[r][lane] > 0.0f)) continue;
        any = true;
        second_readings += r == 1;
        EXPECT_EQ(bits(portable.H[r][lane]), bits(kernel.H[r][lane]));
        EXPECT_EQ(bits(portable.L[r][lane]), bits(kernel.L[r][lane]));
        EXPECT_EQ(bits(portable.tg[r][lane]), bits(kernel.tg[r][lane]));
        EXPECT_EQ(portable.along_v[r][lane], kernel.along_v[r][lane]);
        magnified += portable.H[r][lane] < 1.0f;
        for (int s = 0; s < SelectionLanes::kSlots; ++s) {
          EXPECT_EQ(bits(portable.weight[r][s][lane]), bits(kernel.weight[r][s][lane])) << s;
          if (portable.weight[r][s][lane] > 0.0f) {
            EXPECT_EQ(portable.copy[r][s][lane], kernel.copy[r][s][lane]) << s;
          }
        }
        ASSERT_EQ(portable.probes[r][lane], kernel.probes[r][lane]);
        if (portable.probes[r][lane] > 0) {
          ++probed;
          EXPECT_EQ(bits(portable.probe_step[r][lane]), bits(kernel.probe_step[r][lane]));
          EXPECT_EQ(bits(portable.probe_weight[r][lane]), bits(kernel.probe_weight[r][lane]));
          EXPECT_EQ(bits(portable.probe_end_weight[r][lane]),
                    bits(kernel.probe_end_weight[r][lane]));
        }
        ASSERT_EQ(portable.box_probes[r][lane], kernel.box_probes[r][lane]);
        if (portable.box_probes[r][lane] > 0) {
          ++boxed;
          two_rows += portable.box_probe_rows[r][lane] > 0.0f;
          EXPECT_EQ(bits(portable.box_probe_step[r][lane]), bits(kernel.box_probe_step[r][lane]));
          EXPECT_EQ(bits(portable.box_probe_weight[r][lane]),
                    bits(kernel.box_probe_weight[r][lane]));
          EXPECT_EQ(bits(portable.box_probe_end_weight[r][lane]),
                    bits(kernel.box_probe_end_weight[r][lane]));
          EXPECT_EQ(bits(portable.box_probe_rows[r][lane]), bits(kernel.box_probe_rows[r][lane]));
        }
      }
      auto bits = [](float x) {
        uint32_t b;
        std::memcpy(&b, &x, 4);
        return b;
      };
      ASSERT_EQ(bits(portable.taps_share[lane]), bits(kernel.taps_share[lane]));
      if (portable.taps_share[lane] > 0.0f) {
        any = true;
        ++tapped;
        faded += portable.taps_share[lane] < 1.0f;
        EXPECT_EQ(bits(portable.taps_first[lane]), bits(kernel.taps_first[lane]));
        EXPECT_EQ(bits(portable.taps_weight[lane]), bits(kernel.taps_weight[lane]));
        for (int c = 0; c < 2; ++c) {
          EXPECT_EQ(bits(portable.tap_p[c][lane]), bits(kernel.tap_p[c][lane])) << c;
          EXPECT_EQ(bits(portable.tap_q[c][lane]), bits(kernel.tap_q[c][lane])) << c;
        }
      }
      degenerate += !any;
      const TextureFootprint f{0, 0, d[0][lane], d[1][lane], d[2][lane], d[3][lane]};
      one_of_two += ReadingsOfFootprint(f, kN).count == 2 && portable.reading_weight[0][lane] > 0 &&
                    portable.reading_weight[1][lane] == 0;
      ++compared;
    }
  }
  EXPECT_EQ(compared, 8000);
  // Every class was among them.
  EXPECT_GT(second_readings, 300);
  EXPECT_GT(probed, 300);
  EXPECT_GT(boxed, 100);
  EXPECT_GT(two_rows, 20);
  EXPECT_GT(whole_box_groups, 50);  // where the kernel skips the table's copies
  EXPECT_GT(magnified, 100);
  EXPECT_GT(degenerate, 300);
  EXPECT_GT(one_of_two, 20);
  EXPECT_GT(tapped, 300);
  EXPECT_GT(faded, 20);
  std::printf(
      "lanes compared: %d; second readings %d, probed %d, box probed %d, magnified %d, "
      "tapped %d (faded %d), one of two %d, degenerate %d\n",
      compared, second_readings, probed, boxed, magnified, tapped, faded, one_of_two, degenerate);
}

}  // namespace
}  // namespace aperture
