// The table's shape against seed 000's table for n = 6, the closed forms, the builder against a
// brute-force box-parallelogram integral, and the block's validation.
#include "texture/prefiltered_table.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <random>
#include <set>
#include <utility>
#include <vector>

#include "texture/prefiltered_table_builder.h"

namespace aperture {
namespace {

// Every filled cell of the paper's table for n = 6 (rows H, columns L): lambda, then the copy
// resolution "major x minor" as printed (0 where the scan of the paper lost it).
struct PaperCell {
  int log2_h, log2_l, lambda, major, minor;
};
constexpr PaperCell kPaperTable[] = {
    {0, 0, 1, 64, 64},                                                        //
    {1, 0, 2, 0, 0},   {1, 1, 1, 0, 0},                                       //
    {3, 0, 8, 8, 64},  {3, 1, 4, 8, 32},  {3, 2, 2, 8, 16}, {3, 3, 1, 8, 8},  //
    {4, 0, 16, 4, 64}, {4, 1, 8, 4, 32},  {4, 2, 4, 4, 16}, {4, 3, 2, 4, 8},  //
    {4, 4, 1, 4, 4},                                                          //
    {5, 0, 32, 2, 64}, {5, 1, 16, 2, 32}, {5, 2, 8, 2, 16}, {5, 3, 4, 2, 8},  //
    {5, 4, 2, 2, 4},   {5, 5, 1, 2, 2},                                       //
    {6, 1, 16, 2, 32}, {6, 2, 8, 2, 16},  {6, 3, 4, 2, 8},  {6, 4, 2, 2, 4},  //
    {6, 5, 1, 2, 2},   {6, 6, 1, 1, 1},                                       //
    {7, 2, 8, 2, 16},  {7, 3, 4, 2, 8},   {7, 4, 2, 2, 4},  {7, 5, 1, 2, 2},  //
    {7, 6, 1, 1, 1},                                                          //
    {8, 3, 4, 2, 8},   {8, 4, 2, 2, 4},   {8, 5, 1, 2, 2},  {8, 6, 1, 1, 1},  //
    {9, 4, 2, 2, 4},   {9, 5, 1, 2, 2},   {9, 6, 1, 1, 1},                    //
    {10, 5, 1, 2, 2},  {10, 6, 1, 1, 1},                                      //
    {11, 6, 1, 1, 1},
};

TEST(PrefilteredTableShape, MatchesThePapersTableForN6CellByCell) {
  for (const PaperCell& p : kPaperTable) {
    SCOPED_TRACE(testing::Message() << "H = 2^" << p.log2_h << ", L = 2^" << p.log2_l);
    const CellShape s = TableCellShape(6, p.log2_l, p.log2_h - p.log2_l);
    EXPECT_EQ(s.lambda, static_cast<uint32_t>(p.lambda));
    if (p.major != 0) {
      EXPECT_EQ(s.major, static_cast<uint32_t>(p.major));
      EXPECT_EQ(s.minor, static_cast<uint32_t>(p.minor));
    }
  }
}

TEST(PrefilteredTableShape, ColumnsHoldNCellsFromHEqualsL) {
  // The paper's columns: L = 2^j runs over H = 2^j .. 2^(j+n-1); 42 filled cells for n = 6, and
  // the cell H = 2^6, L = 2^0 is empty.
  std::set<std::pair<int, int>> paper;
  for (const PaperCell& p : kPaperTable) paper.insert({p.log2_h, p.log2_l});
  EXPECT_EQ(paper.size() + 3, 42u);  // the scan lost row H = 2^2 (three cells)
  for (int j = 0; j <= 6; ++j)
    for (int i = 0; i < 6; ++i) EXPECT_GE(TableCellShape(6, j, i).lambda, 1u);
  EXPECT_FALSE(paper.count({6, 0}));
}

TEST(PrefilteredTableShape, EachDiagonalCostsSnAndTheTableNSnPlusTheEndsPlusBase) {
  for (int n = 1; n <= 12; ++n) {
    uint64_t all = 0;
    for (int i = 0; i < n; ++i) {
      uint64_t diagonal = 0;
      for (int j = 0; j <= n; ++j) {
        const CellShape s = TableCellShape(n, j, i);
        diagonal += uint64_t{s.lambda} * s.major * s.minor;
      }
      EXPECT_EQ(diagonal, DiagonalTexels(n)) << "n = " << n << ", diagonal " << i;
      all += diagonal;
    }
    // seed 000: S_n = (4^(n+1) - 1) / 3, so for n = 6: 5461.
    if (n == 6) {
      EXPECT_EQ(DiagonalTexels(6), 5461u);
    }
    // The end tilts: four more copies of major x minor texels in every tilted cell.
    uint64_t ends = 0;
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i < n; ++i) {
        const CellShape s = TableCellShape(n, j, i);
        ends += uint64_t{CellCopies(s.lambda) - s.lambda} * s.major * s.minor;
      }
    EXPECT_EQ(ends, EndTiltTexels(n));
    EXPECT_EQ(all + ends + (uint64_t{1} << (2 * n)), TableTexels(n));
  }
  // For a 1024 x 1024 texture the ends add 19 % to seed 000's table.
  EXPECT_EQ(TableTexels(10) - EndTiltTexels(10), 10 * DiagonalTexels(10) + (1u << 20));
  EXPECT_NEAR(double(TableTexels(10)) / double(TableTexels(10) - EndTiltTexels(10)), 1.19, 0.01);
}

TEST(PrefilteredTableShape, TiltSetsAreThePapersAndTheEnds) {
  EXPECT_EQ(TiltsPerAxis(1), 1u);
  EXPECT_EQ(CellCopies(1), 1u);
  EXPECT_EQ(TiltTangent(1, 0), 0.0f);
  EXPECT_EQ(TiltsPerAxis(2), 1u);  // seed 000's one tilt, 0, per axis
  EXPECT_EQ(CellCopies(2), 2u);
  EXPECT_EQ(TiltTangent(2, 0), 0.0f);
  const float four[] = {-1.0f, -0.5f, 0.5f, 1.0f};
  for (uint32_t k = 0; k < 4; ++k) EXPECT_EQ(TiltTangent(4, k), four[k]);
  const float eight[] = {-1.0f, -0.75f, -0.25f, 0.25f, 0.75f, 1.0f};
  EXPECT_EQ(TiltsPerAxis(8), 6u);
  for (uint32_t k = 0; k < 6; ++k) EXPECT_EQ(TiltTangent(8, k), eight[k]);
  for (uint32_t lambda = 4; lambda <= 512; lambda *= 2) {
    EXPECT_EQ(TiltsPerAxis(lambda), lambda / 2 + 2);
    EXPECT_EQ(TiltTangent(lambda, 0), -1.0f);
    EXPECT_EQ(TiltTangent(lambda, lambda / 2 + 1), 1.0f);
    // Seed 000's tilts, indices 1 .. lambda / 2: level i is level i - 1 plus and minus
    // 2^(1 - i).
    for (uint32_t k = 0; k < lambda / 4; ++k) {
      const float parent = TiltTangent(lambda / 2, k + 1), step = 2.0f / static_cast<float>(lambda);
      EXPECT_FLOAT_EQ(TiltTangent(lambda, 2 * k + 1), parent - step);
      EXPECT_FLOAT_EQ(TiltTangent(lambda, 2 * k + 2), parent + step);
    }
  }
}

Image RandomImage(int size, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> byte(0, 255);
  Image image(size, size);
  for (Rgba& t : image.texels())
    t = {byte(rng) / 255.0f, byte(rng) / 255.0f, byte(rng) / 255.0f, byte(rng) / 255.0f};
  return image;
}

TEST(PrefilteredTableBuilder, BytesAndDirectoryMatchTheClosedForm) {
  for (int n : {1, 3, 6}) {
    auto block = BuildPrefilteredTable(RandomImage(1 << n, 7));
    ASSERT_TRUE(block.ok()) << block.status();
    auto table = block->View();
    ASSERT_TRUE(table.ok()) << table.status();
    uint64_t texels = 0;
    for (const CopyEntry& e : table->directory()) texels += uint64_t{e.width} * e.height;
    EXPECT_EQ(texels, TableTexels(n));
    EXPECT_EQ(table->header().total_bytes - table->header().data_offset, 4 * TableTexels(n));
  }
}

TEST(PrefilteredTableBuilder, ConstantTextureGivesTheConstantInEveryCopy) {
  const Rgba c{51 / 255.0f, 128 / 255.0f, 1.0f, 200 / 255.0f};
  auto block = BuildPrefilteredTable(Image(32, 32, c));
  ASSERT_TRUE(block.ok());
  auto table = block->View();
  ASSERT_TRUE(table.ok());
  for (const CopyEntry& e : table->directory()) {
    const uint8_t* t = table->texels(e);
    for (uint64_t k = 0; k < uint64_t{e.width} * e.height; ++k) {
      ASSERT_EQ(t[4 * k + 0], 51);
      ASSERT_EQ(t[4 * k + 1], 128);
      ASSERT_EQ(t[4 * k + 2], 255);
      ASSERT_EQ(t[4 * k + 3], 200);
    }
  }
}

// Brute force: the average of the piecewise-constant periodic texture over the box
// parallelogram |x - cx| <= H, |(y - cy) - tg (x - cx)| <= L (tilt U), by a fine midpoint grid.
float BruteForce(const Image& img, double cx, double cy, double H, double L, double tg,
                 bool tilt_v) {
  const int N = img.width(), steps_major = 64 * static_cast<int>(H), steps_minor = 64;
  double sum = 0;
  for (int a = 0; a < steps_major; ++a) {
    const double dx = -H + (a + 0.5) * 2 * H / steps_major;
    for (int b = 0; b < steps_minor; ++b) {
      const double dy = tg * dx - L + (b + 0.5) * 2 * L / steps_minor;
      const double major = (tilt_v ? cy : cx) + dx, minor = (tilt_v ? cx : cy) + dy;
      const int x = static_cast<int>(std::floor(tilt_v ? minor : major)) & (N - 1);
      const int y = static_cast<int>(std::floor(tilt_v ? major : minor)) & (N - 1);
      sum += img.at(x, y).r;
    }
  }
  return static_cast<float>(sum / (double(steps_major) * steps_minor));
}

TEST(PrefilteredTableBuilder, CopiesAreTheBoxParallelogramAverages) {
  const int n = 5, N = 1 << n;
  const Image img = RandomImage(N, 11);
  auto block = BuildPrefilteredTable(img);
  ASSERT_TRUE(block.ok());
  auto table = block->View();
  ASSERT_TRUE(table.ok());
  // Cells with tilts, untilted cells, the frozen region and wrap-around across the period.
  const std::pair<int, int> cells[] = {{0, 0}, {0, 2}, {0, 4}, {1, 3}, {2, 1}, {2, 4}, {4, 3}};
  for (auto [j, i] : cells) {
    const PrefilteredTable::Cell& cell = table->cell(j, i);
    for (uint32_t c = 0; c < cell.copies; ++c) {
      const CopyEntry& e = table->copy(cell.first + c);
      const bool tilt_v = e.axis == TiltAxis::kV;
      const double H = std::ldexp(1.0, i + j), L = std::ldexp(1.0, j);
      const double sx = double(N) / (tilt_v ? e.height : e.width);
      const double sy = double(N) / (tilt_v ? e.width : e.height);
      for (uint32_t y = 0; y < e.height; y += std::max(1u, e.height / 4)) {
        for (uint32_t x = 0; x < e.width; x += std::max(1u, e.width / 4)) {
          const double p = tilt_v ? y : x, q = tilt_v ? x : y;  // major, minor index
          const float want =
              BruteForce(img, tilt_v ? (q + 0.5) * sy : (p + 0.5) * sx,
                         tilt_v ? (p + 0.5) * sx : (q + 0.5) * sy, H, L, e.tg, tilt_v);
          const float got = table->texels(e)[4 * (size_t(y) * e.width + x)] / 255.0f;
          ASSERT_NEAR(got, want, 0.012f) << "cell (" << j << ", " << i << ") copy " << c << " tg "
                                         << e.tg << " texel " << x << "," << y;
        }
      }
    }
  }
}

// Every texel of every copy of a small table (all cells: untilted, both tilt axes, the frozen
// region, lines wrapping across the period, tiles whose line count is not a multiple of the
// builder's interleaved lanes) against the brute-force average.
TEST(PrefilteredTableBuilder, EveryTexelOfEveryCopyIsTheBoxParallelogramAverage) {
  for (int n : {1, 2, 4}) {
    const int N = 1 << n;
    const Image img = RandomImage(N, 40 + n);
    auto block = BuildPrefilteredTable(img);
    ASSERT_TRUE(block.ok());
    auto table = block->View();
    ASSERT_TRUE(table.ok());
    for (int j = 0; j <= n; ++j) {
      for (int i = 0; i < n; ++i) {
        const PrefilteredTable::Cell& cell = table->cell(j, i);
        for (uint32_t c = 0; c < cell.copies; ++c) {
          const CopyEntry& e = table->copy(cell.first + c);
          const bool tilt_v = e.axis == TiltAxis::kV;
          const double H = std::ldexp(1.0, i + j), L = std::ldexp(1.0, j);
          const double sx = double(N) / (tilt_v ? e.height : e.width);
          const double sy = double(N) / (tilt_v ? e.width : e.height);
          for (uint32_t y = 0; y < e.height; ++y) {
            for (uint32_t x = 0; x < e.width; ++x) {
              const double p = tilt_v ? y : x, q = tilt_v ? x : y;
              const float want =
                  BruteForce(img, tilt_v ? (q + 0.5) * sy : (p + 0.5) * sx,
                             tilt_v ? (p + 0.5) * sx : (q + 0.5) * sy, H, L, e.tg, tilt_v);
              const float got = table->texels(e)[4 * (size_t(y) * e.width + x)] / 255.0f;
              ASSERT_NEAR(got, want, 0.012f) << "n " << n << " cell (" << j << ", " << i
                                             << ") copy " << c << " texel " << x << "," << y;
            }
          }
        }
      }
    }
  }
}

// The parallel build does not depend on the number of threads.
TEST(PrefilteredTableBuilder, OneAndTwoThreadsBuildTheSameBytes) {
  const Image img = RandomImage(64, 7);
  TableBuildOptions one, two;
  one.threads = 1;
  two.threads = 2;
  auto a = BuildPrefilteredTable(img, one), b = BuildPrefilteredTable(img, two);
  ASSERT_TRUE(a.ok());
  ASSERT_TRUE(b.ok());
  ASSERT_EQ(a->bytes.size(), b->bytes.size());
  const size_t data = a->View()->header().data_offset;
  EXPECT_EQ(std::memcmp(a->bytes.data() + data, b->bytes.data() + data, a->bytes.size() - data), 0);
}

// Progress is reported as an increasing fraction of the work that ends at 1, and does not
// change the table.
TEST(PrefilteredTableBuilder, ReportsIncreasingProgressEndingAtOne) {
  const Image img = RandomImage(64, 3);
  std::vector<double> seen;
  TableBuildOptions options;
  options.progress = [&](double done) { seen.push_back(done); };
  auto with = BuildPrefilteredTable(img, options), without = BuildPrefilteredTable(img);
  ASSERT_TRUE(with.ok() && without.ok());
  ASSERT_GT(seen.size(), 6u);  // at least one report per L
  for (size_t i = 1; i < seen.size(); ++i) EXPECT_GE(seen[i], seen[i - 1]);
  EXPECT_GT(seen.front(), 0.0);
  EXPECT_EQ(seen.back(), 1.0);
  const size_t data = with->View()->header().data_offset;
  EXPECT_EQ(std::memcmp(with->bytes.data() + data, without->bytes.data() + data,
                        with->bytes.size() - data),
            0);
}

TEST(PrefilteredTableBuilder, ResamplesNonPowerOfTwoImages) {
  auto block = BuildPrefilteredTable(Image(20, 12, {0.5f, 0.5f, 0.5f, 1}));
  ASSERT_TRUE(block.ok());
  auto table = block->View();
  ASSERT_TRUE(table.ok());
  EXPECT_EQ(table->size(), 32);
  EXPECT_EQ(table->header().source_width, 20u);
  EXPECT_EQ(table->header().source_height, 12u);
}

TEST(PrefilteredTableView, RejectsBadBlocks) {
  auto block = BuildPrefilteredTable(RandomImage(16, 3));
  ASSERT_TRUE(block.ok());
  std::vector<std::byte> bytes = block->bytes;
  EXPECT_TRUE(PrefilteredTable::View(bytes).ok());
  // Truncated.
  EXPECT_FALSE(PrefilteredTable::View(std::span(bytes).first(bytes.size() - 4)).ok());
  // Wrong magic: FailedPrecondition ("not mine"), the others InvalidArgument.
  std::vector<std::byte> other = bytes;
  other[0] = std::byte{'X'};
  EXPECT_EQ(PrefilteredTable::View(other).status().code(), absl::StatusCode::kFailedPrecondition);
  // A directory entry that lies about its size.
  std::vector<std::byte> lying = bytes;
  TableHeader h;
  std::memcpy(&h, lying.data(), sizeof(h));
  CopyEntry e;
  std::memcpy(&e, lying.data() + h.directory_offset + sizeof(CopyEntry) * 3, sizeof(e));
  e.width *= 2;
  std::memcpy(lying.data() + h.directory_offset + sizeof(CopyEntry) * 3, &e, sizeof(e));
  EXPECT_EQ(PrefilteredTable::View(lying).status().code(), absl::StatusCode::kInvalidArgument);
  // A copy between texels (its offset not a whole texel from the base's), or a base moved up
  // a row past another copy: inside the block, but not where the samplers' 32-bit texel
  // indices from the base reach.
  for (const bool before_base : {false, true}) {
    std::vector<std::byte> moved = bytes;
    const size_t at = h.directory_offset + sizeof(CopyEntry) * 5, base_at = h.directory_offset;
    CopyEntry copy, base;
    std::memcpy(&copy, moved.data() + at, sizeof(copy));
    std::memcpy(&base, moved.data() + base_at, sizeof(base));
    if (before_base) {
      copy.offset = base.offset;
      base.offset += 4 * base.width;
    } else {
      copy.offset += 2;
    }
    std::memcpy(moved.data() + at, &copy, sizeof(copy));
    std::memcpy(moved.data() + base_at, &base, sizeof(base));
    const auto view = PrefilteredTable::View(moved);
    EXPECT_EQ(view.status().code(), absl::StatusCode::kInvalidArgument) << before_base;
    EXPECT_NE(view.status().message().find("32-bit texel index"), std::string::npos)
        << view.status();
  }
  // Version from the future.
  std::vector<std::byte> future = bytes;
  h.version = kTableVersion + 1;
  std::memcpy(future.data(), &h, sizeof(h));
  EXPECT_FALSE(PrefilteredTable::View(future).ok());
}

TEST(PrefilteredTableFile, RoundTripsAndRecognisesForeignFiles) {
  auto block = BuildPrefilteredTable(RandomImage(16, 5));
  ASSERT_TRUE(block.ok());
  const std::string path =
      (std::filesystem::temp_directory_path() / "aperture_table_test.apt").string();
  ASSERT_TRUE(WriteTableFile(path, *block).ok());
  auto read = ReadTableFile(path);
  ASSERT_TRUE(read.ok()) << read.status();
  EXPECT_EQ(read->bytes, block->bytes);
  EXPECT_TRUE(read->View().ok());
  {
    std::FILE* f = std::fopen(path.c_str(), "wb");
    std::fputs("P6 not a table at all, just some other file of more than 64 bytes............", f);
    std::fclose(f);
  }
  EXPECT_EQ(ReadTableFile(path).status().code(), absl::StatusCode::kFailedPrecondition);
  std::filesystem::remove(path);
  EXPECT_EQ(ReadTableFile(path).status().code(), absl::StatusCode::kNotFound);
}

}  // namespace
}  // namespace aperture
