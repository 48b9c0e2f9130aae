// aperture-server --metrics-listen: a real server with bearer tokens renders a frame and refuses
// an unauthenticated call; its endpoint answers the Prometheus text format, which Debian's
// `promtool check metrics` accepts (the test fails, not skips, without promtool: it is in
// scripts/debian-packages.txt), counts the frame and the refusal, and serves nothing but
// /metrics. A malformed address stops the start.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <httplib.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "absl/strings/numbers.h"
#include "integration/server_process.h"

namespace aperture::testing {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

constexpr const char* kPromtool = "/usr/bin/promtool";

class MetricsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::path(::testing::TempDir()) / ("aperture_metrics_" + std::to_string(getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string WriteFile(const std::string& name, const std::string& content) {
    const fs::path path = dir_ / name;
    std::ofstream(path) << content;
    return path.string();
  }

  fs::path dir_;
};

// The HOST and PORT of the server's "metrics on http://HOST:PORT/metrics" log line.
bool MetricsAddress(const std::string& log, std::string* host, int* port) {
  const std::string prefix = "metrics on http://";
  const size_t at = log.find(prefix);
  if (at == std::string::npos) return false;
  const size_t start = at + prefix.size();
  const size_t path = log.find("/metrics", start);
  const size_t colon = log.rfind(':', path);
  if (path == std::string::npos || colon == std::string::npos || colon < start) return false;
  *host = log.substr(start, colon - start);
  return absl::SimpleAtoi(log.substr(colon + 1, path - colon - 1), port);
}

TEST_F(MetricsTest, PromtoolAcceptsTheMetricsAndTheyCountAFrameAndARefusal) {
  ASSERT_TRUE(fs::exists(kPromtool))
      << kPromtool << " is missing: apt-get install prometheus (scripts/debian-packages.txt)";
  const std::string tokens = WriteFile("tokens", "metrics-test-token\n");
  const std::string token_file = WriteFile("token", "metrics-test-token\n");
  std::string error;
  auto server = ServerProcess::Start(
      {"--metrics-listen=127.0.0.1:0", "--auth-tokens=" + tokens, "--threads=2"}, &error);
  ASSERT_NE(server, nullptr) << error;
  std::string host;
  int port = 0;
  ASSERT_TRUE(MetricsAddress(server->Log(), &host, &port)) << server->Log();
  EXPECT_EQ(host, "127.0.0.1");

  const CommandResult rendered = RunCommand(
      {APERTURE_CLIENT_BIN, "render", "--server=" + server->address(), "--token-file=" + token_file,
       "--scene=airport", "--size=64x36", "--deadline-s=30", "-o=" + (dir_ / "f.exr").string()},
      60);
  ASSERT_EQ(rendered.exit_code, 0) << rendered.err;
  const CommandResult refused =
      RunCommand({APERTURE_CLIENT_BIN, "info", "--server=" + server->address()}, 30);
  EXPECT_EQ(refused.exit_code, 1) << refused.err;
  EXPECT_THAT(refused.err, HasSubstr("authorization: Bearer"));

  httplib::Client http(host, port);
  http.set_connection_timeout(5);
  http.set_read_timeout(10);
  const httplib::Result scrape = http.Get("/metrics");
  ASSERT_TRUE(scrape) << "no answer from " << host << ":" << port;
  EXPECT_EQ(scrape->status, 200);
  EXPECT_EQ(scrape->get_header_value("Content-Type"), "text/plain; version=0.0.4; charset=utf-8");
  const std::string& text = scrape->body;

  const std::string path = WriteFile("metrics.txt", text);
  const CommandResult check =
      RunCommand({"/bin/sh", "-c", std::string(kPromtool) + " check metrics < " + path}, 60);
  EXPECT_EQ(check.exit_code, 0) << check.out << check.err << "\n" << text;

  EXPECT_THAT(text, HasSubstr("aperture_auth_refusals_total{method=\"aperture.v1.Render/"
                              "GetServerInfo\"} 1\n"));
  EXPECT_THAT(text, HasSubstr("aperture_rpcs_total{method=\"aperture.v1.Render/GetServerInfo\","
                              "code=\"UNAUTHENTICATED\"} 1\n"));
  EXPECT_THAT(text, HasSubstr("aperture_rpcs_total{method=\"aperture.v1.Render/RenderFrame\","
                              "code=\"OK\"} 1\n"));
  EXPECT_THAT(text, HasSubstr("aperture_frames_total{mode=\"raster\",status=\"OK\"} 1\n"));
  for (const char* stage : {"queue", "raster", "encode", "send"})
    EXPECT_THAT(text, HasSubstr(std::string("aperture_frame_stage_seconds_count{stage=\"") + stage +
                                "\"} 1\n"));
  EXPECT_THAT(text, HasSubstr("aperture_frame_latency_seconds_count{mode=\"raster\"} 1\n"));
  EXPECT_THAT(text, HasSubstr("aperture_admission_queue_depth 0\n"));
  EXPECT_THAT(text, HasSubstr("aperture_scenes_loaded 1\n"));
  EXPECT_THAT(text, HasSubstr("# TYPE aperture_store_evictions_total counter\n"));

  // Nothing but the metrics answers 200.
  for (const char* other : {"/", "/metrics/", "/metricsz", "/index.html", "/debug/vars"}) {
    const httplib::Result answer = http.Get(other);
    ASSERT_TRUE(answer) << other;
    EXPECT_EQ(answer->status, 404) << other;
  }
  const httplib::Result post = http.Post("/metrics", "x", "text/plain");
  ASSERT_TRUE(post);
  EXPECT_NE(post->status, 200);
}

TEST_F(MetricsTest, AMalformedAddressStopsTheStart) {
  for (const char* address : {"nonsense", "127.0.0.1:99999", "127.0.0.1:"}) {
    const CommandResult start =
        RunCommand({APERTURE_SERVER_BIN, "--listen=127.0.0.1:0", "--store=none",
                    std::string("--metrics-listen=") + address},
                   30);
    EXPECT_EQ(start.exit_code, 2) << address << ": " << start.err;
    EXPECT_THAT(start.err, HasSubstr("--metrics-listen")) << address;
  }
}

}  // namespace
}  // namespace aperture::testing
