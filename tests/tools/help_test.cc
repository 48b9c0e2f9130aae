// Every binary answers --help with its own flags and --version with the project's version, exit 0
// (absl's own --help exits 1 and printed "No flags matched." for these binaries).
#include <gtest/gtest.h>

#include <string>

#include "support/run_process.h"

namespace aperture::testing {
namespace {

struct Binary {
  const char* path;
  const char* name;
  const char* flag;  // one of its own flags the help must list
};

const Binary kBinaries[] = {{APERTURE_RENDER_BIN, "aperture-render", "--zip-level"},
                            {APERTURE_SERVER_BIN, "aperture-server", "--max-queue"},
                            {APERTURE_CLIENT_BIN, "aperture", "--concurrency"}};

TEST(Help, EveryBinaryListsItsOwnFlagsAndExitsZero) {
  for (const Binary& b : kBinaries) {
    for (const char* ask : {"--help", "-h"}) {
      const ProcessResult r = RunProcess(std::string(b.path) + " " + ask);
      EXPECT_EQ(r.exit_code, 0) << b.name << " " << ask << ": " << r.output;
      EXPECT_NE(r.output.find(std::string(b.name) + ": "), std::string::npos) << r.output;
      EXPECT_NE(r.output.find(b.flag), std::string::npos) << b.name << ": " << r.output;
      EXPECT_EQ(r.output.find("No flags matched"), std::string::npos) << r.output;
      EXPECT_EQ(r.output.find("--flagfile"), std::string::npos) << "absl's own flags listed";
    }
    const ProcessResult v = RunProcess(std::string(b.path) + " --version");
    EXPECT_EQ(v.exit_code, 0) << b.name;
    EXPECT_EQ(v.output, std::string(b.name) + " " + APERTURE_VERSION + "\n");
  }
}

TEST(Help, TheTextureToolHasItsOwnHelpAndTheVersion) {
  const ProcessResult help = RunProcess(std::string(APERTURE_TEX_BIN) + " --help");
  EXPECT_EQ(help.exit_code, 0) << help.output;
  EXPECT_NE(help.output.find("bake"), std::string::npos) << help.output;
  const ProcessResult v = RunProcess(std::string(APERTURE_TEX_BIN) + " --version");
  EXPECT_EQ(v.exit_code, 0);
  EXPECT_EQ(v.output, std::string("aperture-tex ") + APERTURE_VERSION + "\n");
}

// The benchmarks are the lab's aperture-bench, not commands of the installed aperture-tex.
TEST(Help, TheBenchmarksAreApertureBenchsNotTheTextureTools) {
  const ProcessResult tex = RunProcess(std::string(APERTURE_TEX_BIN) + " --help");
  EXPECT_EQ(tex.output.find("bench"), std::string::npos) << tex.output;
  const ProcessResult moved = RunProcess(std::string(APERTURE_TEX_BIN) + " bench-filter");
  EXPECT_EQ(moved.exit_code, 2) << moved.output;
  const ProcessResult bench = RunProcess(std::string(APERTURE_BENCH_BIN) + " --help");
  EXPECT_EQ(bench.exit_code, 0) << bench.output;
  for (const char* command : {"filter", "flicker", "packed"})
    EXPECT_NE(bench.output.find(std::string("  ") + command + " "), std::string::npos)
        << command << ": " << bench.output;
  const ProcessResult v = RunProcess(std::string(APERTURE_BENCH_BIN) + " --version");
  EXPECT_EQ(v.output, std::string("aperture-bench ") + APERTURE_VERSION + "\n");
}

TEST(Help, TheFilterBenchmarkListsPositionsAndRefusesABadCountNamingIt) {
  const std::string bench = std::string(APERTURE_BENCH_BIN) + " filter";
  const ProcessResult help = RunProcess(bench + " --help");
  EXPECT_EQ(help.exit_code, 0) << help.output;
  EXPECT_NE(help.output.find("--positions P"), std::string::npos) << help.output;
  // Refused before any texture is loaded or directory made.
  const std::string out = ::testing::TempDir() + "bench_filter_refused";
  for (const char* bad : {"0", "65", "x"}) {
    const ProcessResult r = RunProcess(bench + " --positions " + bad + " --out " + out);
    EXPECT_EQ(r.exit_code, 2) << bad << ": " << r.output;
    EXPECT_NE(r.output.find("--positions 1..64"), std::string::npos) << r.output;
  }
  EXPECT_EQ(RunProcess("test -e " + out).exit_code, 1) << out << " was made";
  // A repeated option: the last value counts (were it the first, the bad angle would be named).
  const ProcessResult last = RunProcess(bench + " --positions 2 --positions 0 --angles 95");
  EXPECT_EQ(last.exit_code, 2) << last.output;
  EXPECT_NE(last.output.find("--positions 1..64"), std::string::npos) << last.output;
}

TEST(Help, AnUnknownFlagIsAUsageErrorNamingIt) {
  for (const Binary& b : kBinaries) {
    const ProcessResult r = RunProcess(std::string(b.path) + " --frobnicate=3");
    EXPECT_EQ(r.exit_code, 2) << b.name << ": " << r.output;
    EXPECT_NE(r.output.find("unknown flag '--frobnicate=3'"), std::string::npos) << r.output;
  }
  // Values that start with '-' and negated booleans are not unknown flags.
  const ProcessResult ok = RunProcess(std::string(APERTURE_RENDER_BIN) +
                                      " --camera 0,14,420,0,-5,0 --near 0.5 --nopreview --size "
                                      "8x8 --filter trilinear -o /dev/null --store none");
  EXPECT_EQ(ok.exit_code, 0) << ok.output;
}

TEST(Help, AClientCommandListsItsFlagsOnly) {
  const ProcessResult sim = RunProcess(std::string(APERTURE_CLIENT_BIN) + " sim --help");
  EXPECT_EQ(sim.exit_code, 0) << sim.output;
  const size_t at = sim.output.find("flags of 'sim':");
  ASSERT_NE(at, std::string::npos) << sim.output;
  const std::string flags = sim.output.substr(at);  // after the usage lines of every command
  EXPECT_NE(flags.find("--channels"), std::string::npos);
  EXPECT_NE(flags.find("--server"), std::string::npos);         // common to all
  EXPECT_EQ(flags.find("--concurrency"), std::string::npos);    // load and batch only
  EXPECT_EQ(flags.find("--contact-sheet"), std::string::npos);  // batch only
}

}  // namespace
}  // namespace aperture::testing
