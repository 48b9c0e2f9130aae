// --cost-model: the tile cost model is named on the command line, never looked
// for in the build folder; a missing or malformed file is an error naming it, and a good one is
// the one the frame is planned with.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "support/run_process.h"

namespace aperture::testing {
namespace {

std::string WriteFile(const std::string& name, const std::string& text) {
  const std::string path =
      (std::filesystem::temp_directory_path() / ("aperture_cost_model_test_" + name)).string();
  std::ofstream(path) << text;
  return path;
}

TEST(CostModelFlag, TheServerRefusesToStartWithABadModelNamingIt) {
  const std::string malformed = WriteFile("malformed.txt", "0.001 -2\n");
  for (const std::string& path : {std::string("/nonexistent/cost_model.txt"), malformed}) {
    const ProcessResult r = RunProcess(std::string(APERTURE_SERVER_BIN) +
                                       " --listen 127.0.0.1:0 --store none --cost-model " + path);
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("--cost-model"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find(path), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("listening"), std::string::npos) << r.output;
  }
  std::filesystem::remove(malformed);
}

TEST(CostModelFlag, TheRendererPlansWithTheNamedModelAndSaysWhich) {
  const std::string good = WriteFile("good.txt", "0.001 0.05 0.15\n");
  const std::string base = std::string(APERTURE_RENDER_BIN) +
                           " --scene triangles --size 32x18 --store none --nopreview -o /dev/null";
  const ProcessResult r = RunProcess(base + " --cost-model " + good);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("cost model: " + good), std::string::npos) << r.output;
  // The environment can name it instead.
  const ProcessResult env = RunProcess("APERTURE_COST_MODEL=" + good + " " + base);
  EXPECT_NE(env.output.find("cost model: " + good), std::string::npos) << env.output;
  const ProcessResult missing = RunProcess(base + " --cost-model /nonexistent/model.txt");
  EXPECT_EQ(missing.exit_code, 2) << missing.output;
  EXPECT_NE(missing.output.find("/nonexistent/model.txt"), std::string::npos) << missing.output;
  std::filesystem::remove(good);
}

}  // namespace
}  // namespace aperture::testing
