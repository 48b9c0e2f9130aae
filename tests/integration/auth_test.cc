// Bearer-token authentication: a server started with --auth-tokens refuses
// every Render RPC without an accepted token, keeps gRPC's health service open, reloads the file
// on SIGHUP and never writes a token to its log; without authentication it will not listen
// beyond loopback unless told to.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>

#include "integration/server_process.h"

namespace aperture::testing {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::Not;

class AuthTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::path(::testing::TempDir()) / ("aperture_auth_" + std::to_string(getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string WriteFile(const std::string& name, const std::string& content) {
    const fs::path path = dir_ / name;
    std::ofstream(path) << content;
    return path.string();
  }

  CommandResult Client(const std::string& command, const std::string& address,
                       std::vector<std::string> extra) {
    std::vector<std::string> argv = {APERTURE_CLIENT_BIN, command, "--server=" + address,
                                     "--deadline-s=20"};
    argv.insert(argv.end(), extra.begin(), extra.end());
    return RunCommand(argv, 60);
  }

  CommandResult Render(const std::string& address, std::vector<std::string> extra) {
    extra.insert(extra.end(), {"--scene=triangles", "--size=32x24", "--filter=trilinear",
                               "-o=" + (dir_ / "f.exr").string()});
    return Client("render", address, extra);
  }

  fs::path dir_;
};

TEST_F(AuthTest, EveryRenderCallNeedsAnAcceptedTokenAndHealthStaysOpen) {
  const std::string tokens =
      WriteFile("tokens", "# render farm\nfirst-secret-token\n\n  second-token  \n");
  std::string error;
  auto server = ServerProcess::Start({"--auth-tokens=" + tokens}, &error);
  ASSERT_NE(server, nullptr) << error;

  const CommandResult health = Client("health", server->address(), {});
  EXPECT_EQ(health.exit_code, 0) << health.err;

  const CommandResult anonymous = Client("info", server->address(), {});
  EXPECT_EQ(anonymous.exit_code, 1);
  EXPECT_THAT(anonymous.err, HasSubstr("authorization: Bearer"));

  const CommandResult wrong =
      Render(server->address(), {"--token-file=" + WriteFile("w", "nope\n")});
  EXPECT_EQ(wrong.exit_code, 1);
  EXPECT_THAT(wrong.err, HasSubstr("the token is not accepted"));
  EXPECT_FALSE(fs::exists(dir_ / "f.exr"));

  // Surrounding blanks and comment lines of both files are not part of a token.
  const CommandResult from_file =
      Render(server->address(), {"--token-file=" + WriteFile("c", "# mine\nsecond-token\n")});
  EXPECT_EQ(from_file.exit_code, 0) << from_file.err;
  EXPECT_TRUE(fs::exists(dir_ / "f.exr"));

  const std::string log = server->Log();
  EXPECT_THAT(log, HasSubstr("status=UNAUTHENTICATED"));
  EXPECT_THAT(log, Not(HasSubstr("second-token")));
  EXPECT_THAT(log, Not(HasSubstr("nope")));
}

TEST_F(AuthTest, SighupReloadsTheTokensAndABrokenFileKeepsTheOldOnes) {
  const std::string tokens = WriteFile("tokens", "old-token\n");
  std::string error;
  auto server = ServerProcess::Start({"--auth-tokens=" + tokens}, &error);
  ASSERT_NE(server, nullptr) << error;
  const std::string old_file = WriteFile("old", "old-token\n");
  const std::string new_file = WriteFile("new", "new-token\n");
  EXPECT_EQ(Client("info", server->address(), {"--token-file=" + old_file}).exit_code, 0);

  auto reload = [&](int expected_reloads) {
    server->Signal(SIGHUP);
    // The reload is logged; wait for its line rather than for a fixed time.
    for (int i = 0; i < 200; ++i) {
      const std::string log = server->Log();
      size_t count = 0;
      for (size_t at = log.find("SIGHUP"); at != std::string::npos; at = log.find("SIGHUP", at + 1))
        ++count;
      if (static_cast<int>(count) >= expected_reloads) return;
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    FAIL() << "no SIGHUP line in the log: " << server->Log();
  };
  WriteFile("tokens", "new-token\n");
  reload(1);
  EXPECT_EQ(Client("info", server->address(), {"--token-file=" + new_file}).exit_code, 0);
  EXPECT_EQ(Client("info", server->address(), {"--token-file=" + old_file}).exit_code, 1);

  WriteFile("tokens", "# emptied by mistake\n");
  reload(2);
  EXPECT_THAT(server->Log(), HasSubstr("the tokens accepted before stay"));
  EXPECT_EQ(Client("info", server->address(), {"--token-file=" + new_file}).exit_code, 0);
  EXPECT_EQ(server->WaitForExit(0), std::nullopt) << "SIGHUP must not stop the server";
}

TEST_F(AuthTest, WithoutAuthenticationOnlyLoopbackIsServed) {
  const CommandResult any =
      RunCommand({APERTURE_SERVER_BIN, "--listen=0.0.0.0:0", "--store=none"}, 20);
  EXPECT_EQ(any.exit_code, 2);
  EXPECT_THAT(any.err, HasSubstr("--insecure-listen-any"));
  EXPECT_THAT(any.err, HasSubstr("--auth-tokens"));

  const CommandResult empty =
      RunCommand({APERTURE_SERVER_BIN, "--listen=127.0.0.1:0", "--store=none",
                  "--auth-tokens=" + WriteFile("empty", "\n# nothing\n")},
                 20);
  EXPECT_EQ(empty.exit_code, 2);
  EXPECT_THAT(empty.err, HasSubstr("no token in the file"));

  const CommandResult missing = Client("info", "127.0.0.1:1", {"--token-file=/no/such/token"});
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_THAT(missing.err, HasSubstr("/no/such/token"));

  std::string error;
  auto loopback = ServerProcess::Start({}, &error);
  ASSERT_NE(loopback, nullptr) << error;
  for (int i = 0; i < 200 && loopback->Log().find("auth=") == std::string::npos; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  EXPECT_THAT(loopback->Log(), HasSubstr("auth=none (loopback only)"));
}

}  // namespace
}  // namespace aperture::testing
