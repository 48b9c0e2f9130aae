// TLS on the service: a server started with --tls-cert/--tls-key talks only TLS, and
// the client reaches it with --tls-ca. The certificate is made for the test by openssl.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "integration/server_process.h"

namespace aperture::testing {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

class TlsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::path(::testing::TempDir()) / ("aperture_tls_" + std::to_string(getpid()));
    fs::create_directories(dir_);
    // A self-signed certificate for the loopback address the tests connect to.
    const CommandResult made = RunCommand(
        {"/usr/bin/openssl", "req", "-x509", "-newkey", "rsa:2048", "-nodes", "-days", "1", "-subj",
         "/CN=localhost", "-addext", "subjectAltName=IP:127.0.0.1,DNS:localhost", "-keyout",
         (dir_ / "key.pem").string(), "-out", (dir_ / "cert.pem").string()},
        60);
    ASSERT_EQ(made.exit_code, 0) << made.err;
  }
  void TearDown() override { fs::remove_all(dir_); }

  CommandResult Client(const std::string& command, const std::string& address,
                       std::vector<std::string> extra) {
    std::vector<std::string> argv = {APERTURE_CLIENT_BIN, command, "--server=" + address};
    argv.insert(argv.end(), extra.begin(), extra.end());
    return RunCommand(argv, 60);
  }

  fs::path dir_;
};

TEST_F(TlsTest, AServerWithACertificateAnswersOnlyOverTls) {
  std::string error;
  auto server = ServerProcess::Start(
      {"--tls-cert=" + (dir_ / "cert.pem").string(), "--tls-key=" + (dir_ / "key.pem").string()},
      &error);
  ASSERT_NE(server, nullptr) << error;
  const std::string ca = "--tls-ca=" + (dir_ / "cert.pem").string();

  const CommandResult healthy = Client("health", server->address(), {ca});
  EXPECT_EQ(healthy.exit_code, 0) << healthy.err;

  const CommandResult rendered = Client("render", server->address(),
                                        {ca, "--scene=demo", "--size=64x48", "--filter=trilinear",
                                         "-o=" + (dir_ / "f.exr").string()});
  EXPECT_EQ(rendered.exit_code, 0) << rendered.err;
  EXPECT_TRUE(fs::exists(dir_ / "f.exr"));

  // A plaintext client gets nowhere.
  const CommandResult plain = Client("health", server->address(), {"--deadline-s=3"});
  EXPECT_NE(plain.exit_code, 0);
}

// Mutual TLS: with --tls-client-ca the server serves only clients whose
// certificate that CA signed.
TEST_F(TlsTest, WithAClientCaOnlyClientsWithASignedCertificateAreServed) {
  auto run = [&](std::vector<std::string> argv) {
    const CommandResult result = RunCommand(argv, 60);
    EXPECT_EQ(result.exit_code, 0) << result.err;
  };
  auto path = [&](const std::string& name) { return (dir_ / name).string(); };
  run({"/usr/bin/openssl", "req", "-x509", "-newkey", "rsa:2048", "-nodes", "-days", "1", "-subj",
       "/CN=aperture-test-ca", "-keyout", path("ca.key"), "-out", path("ca.pem")});
  std::ofstream(path("server.ext")) << "subjectAltName=IP:127.0.0.1,DNS:localhost\n";
  std::ofstream(path("client.ext")) << "extendedKeyUsage=clientAuth\n";
  for (const std::string who : {"server", "client"}) {
    run({"/usr/bin/openssl", "req", "-newkey", "rsa:2048", "-nodes", "-subj", "/CN=" + who,
         "-keyout", path(who + ".key"), "-out", path(who + ".csr")});
    run({"/usr/bin/openssl", "x509", "-req", "-in", path(who + ".csr"), "-CA", path("ca.pem"),
         "-CAkey", path("ca.key"), "-CAcreateserial", "-days", "1", "-extfile", path(who + ".ext"),
         "-out", path(who + ".pem")});
  }
  std::string error;
  auto server =
      ServerProcess::Start({"--tls-cert=" + path("server.pem"), "--tls-key=" + path("server.key"),
                            "--tls-client-ca=" + path("ca.pem")},
                           &error);
  ASSERT_NE(server, nullptr) << error;
  const std::string ca = "--tls-ca=" + path("ca.pem");

  const CommandResult signed_client =
      Client("info", server->address(),
             {ca, "--tls-cert=" + path("client.pem"), "--tls-key=" + path("client.key")});
  EXPECT_EQ(signed_client.exit_code, 0) << signed_client.err;

  // TLS without a client certificate, and a certificate no trusted CA signed, are refused.
  const CommandResult no_certificate = Client("info", server->address(), {ca, "--deadline-s=5"});
  EXPECT_NE(no_certificate.exit_code, 0);
  const CommandResult self_signed = Client(
      "info", server->address(),
      {ca, "--deadline-s=5", "--tls-cert=" + path("cert.pem"), "--tls-key=" + path("key.pem")});
  EXPECT_NE(self_signed.exit_code, 0);

  const CommandResult half = RunCommand({APERTURE_SERVER_BIN, "--listen=127.0.0.1:0",
                                         "--store=none", "--tls-client-ca=" + path("ca.pem")},
                                        20);
  EXPECT_EQ(half.exit_code, 2);
  EXPECT_THAT(half.err, HasSubstr("--tls-client-ca needs --tls-cert and --tls-key"));
}

TEST_F(TlsTest, HalfATlsConfigurationOrAnUnreadableCaIsAClearError) {
  const CommandResult half =
      RunCommand({APERTURE_SERVER_BIN, "--listen=127.0.0.1:0", "--store=none",
                  "--tls-cert=" + (dir_ / "cert.pem").string()},
                 20);
  EXPECT_EQ(half.exit_code, 2);
  EXPECT_THAT(half.err, HasSubstr("--tls-cert and --tls-key go together"));

  const CommandResult missing =
      Client("health", "127.0.0.1:1", {"--tls-ca=" + (dir_ / "no-such.pem").string()});
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_THAT(missing.err, HasSubstr("no-such.pem"));
}

}  // namespace
}  // namespace aperture::testing
