// aperture-bench filter run end to end as a user runs it, on a cheap view (pitch 60, coarse
// references): every mode's PSNR and timing printed, OpenImageIO's two peers among them, the
// spread across the yaws, the references cached per position and the row plots written.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "support/run_process.h"

namespace aperture::testing {
namespace {

// The cells of the markdown table row that starts with `prefix`, or empty.
std::vector<std::string> RowCells(const std::string& output, const std::string& prefix) {
  std::istringstream lines(output);
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind(prefix, 0) != 0) continue;
    std::vector<std::string> cells;
    std::istringstream row(line.substr(1));
    for (std::string cell; std::getline(row, cell, '|');) {
      const size_t a = cell.find_first_not_of(' '), b = cell.find_last_not_of(' ');
      cells.push_back(a == std::string::npos ? "" : cell.substr(a, b - a + 1));
    }
    return cells;
  }
  return {};
}

TEST(BenchFilter, ScoresEveryModeAndBothOpenImageIoPeersFromEachYawAndCachesTheReferences) {
  const std::filesystem::path out = std::filesystem::path(::testing::TempDir()) / "bench_filter";
  std::filesystem::remove_all(out);
  const ProcessResult r =
      RunProcess(std::string(APERTURE_BENCH_BIN) +
                 " filter --textures checker --angles 60 --yaws 0,90 --apertures 1 --positions 2"
                 " --ref-min 2 --ref-density 1 --ref-max 8 --timing-rows 64 --out " +
                 out.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::vector<std::string> header = RowCells(r.output, "| texture | theta |");
  ASSERT_EQ(header.size(), 16u) << r.output;
  EXPECT_EQ(header[6], "aniso dB");
  EXPECT_EQ(header[7], "oiio dB");
  EXPECT_EQ(header[8], "oiio16 dB");
  EXPECT_EQ(header[9], "aniso - best oiio");
  for (const char* yaw : {"0", "90"}) {
    const std::vector<std::string> row =
        RowCells(r.output, std::string("| checker | 60 | ") + yaw + " | 1 |");
    ASSERT_EQ(row.size(), header.size()) << yaw << "\n" << r.output;
    // The four modes' PSNRs: a smooth, magnified view every filter renders well.
    double psnr[4];
    for (int m = 0; m < 4; ++m) {
      psnr[m] = std::atof(row[5 + m].c_str());
      EXPECT_GT(psnr[m], 25) << header[5 + m] << " at yaw " << yaw;
      EXPECT_LT(psnr[m], 99) << header[5 + m] << " at yaw " << yaw;
    }
    // The lead is over the better of the two OpenImageIO peers.
    EXPECT_NEAR(std::atof(row[9].c_str()), psnr[1] - std::max(psnr[2], psnr[3]), 0.011);
    for (int m = 0; m < 4; ++m) EXPECT_GT(std::atof(row[11 + m].c_str()), 0) << header[11 + m];
    EXPECT_TRUE(
        std::filesystem::exists(out / (std::string("checker_p60_y") + yaw + "_a1_rows.png")));
    EXPECT_TRUE(
        std::filesystem::exists(out / (std::string("checker_p60_y") + yaw + "_a1_oiio16.exr")));
  }
  const std::vector<std::string> spread = RowCells(r.output, "| checker | 60 | 1 |");
  ASSERT_EQ(spread.size(), 7u) << r.output;
  for (int m = 3; m < 7; ++m) EXPECT_NE(spread[m].find(" ("), std::string::npos) << spread[m];
  // One reference per yaw and position, in the cache folder of --out.
  int references = 0;
  for (const auto& entry : std::filesystem::directory_iterator(out / "cache"))
    references += entry.path().filename().string().rfind("ref_checker_1024_p60_", 0) == 0;
  EXPECT_EQ(references, 4);
  std::filesystem::remove_all(out);
}

}  // namespace
}  // namespace aperture::testing
