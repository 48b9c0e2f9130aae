#include "channel.h"

#include <grpcpp/support/client_interceptor.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "absl/flags/flag.h"
#include "absl/strings/ascii.h"
#include "client_flags.h"
#include "keepalive.h"

namespace aperture {
namespace {

std::string ReadFileOrExit(const std::string& flag, const std::string& path) {
  std::ifstream in(path);
  std::ostringstream content;
  content << in.rdbuf();
  if (!in || content.str().empty()) {
    std::fprintf(stderr, "aperture: %s %s: cannot read the file\n", flag.c_str(), path.c_str());
    std::exit(2);
  }
  return content.str();
}

// Adds `authorization: Bearer <token>` to every call of the channel (gRPC's call credentials
// would refuse to travel over a plaintext loopback channel).
class BearerTokenInterceptor final : public grpc::experimental::Interceptor {
 public:
  explicit BearerTokenInterceptor(const std::string& header) : header_(header) {}
  void Intercept(grpc::experimental::InterceptorBatchMethods* methods) override {
    if (methods->QueryInterceptionHookPoint(
            grpc::experimental::InterceptionHookPoints::PRE_SEND_INITIAL_METADATA))
      methods->GetSendInitialMetadata()->insert({"authorization", header_});
    methods->Proceed();
  }

 private:
  const std::string& header_;
};

class BearerTokenInterceptorFactory final
    : public grpc::experimental::ClientInterceptorFactoryInterface {
 public:
  explicit BearerTokenInterceptorFactory(std::string token) : header_("Bearer " + token) {}
  grpc::experimental::Interceptor* CreateClientInterceptor(
      grpc::experimental::ClientRpcInfo*) override {
    return new BearerTokenInterceptor(header_);
  }

 private:
  const std::string header_;
};

}  // namespace

std::shared_ptr<grpc::ChannelCredentials> ClientCredentials() {
  const std::string ca = absl::GetFlag(FLAGS_tls_ca);
  const std::string cert = absl::GetFlag(FLAGS_tls_cert), key = absl::GetFlag(FLAGS_tls_key);
  if (ca.empty()) {
    if (!cert.empty() || !key.empty()) {
      std::fprintf(stderr, "aperture: --tls-cert and --tls-key need --tls-ca (TLS)\n");
      std::exit(2);
    }
    return grpc::InsecureChannelCredentials();
  }
  if (cert.empty() != key.empty()) {
    std::fprintf(stderr, "aperture: --tls-cert and --tls-key go together\n");
    std::exit(2);
  }
  grpc::SslCredentialsOptions options;
  options.pem_root_certs = ReadFileOrExit("--tls-ca", ca);
  if (!cert.empty()) {
    options.pem_cert_chain = ReadFileOrExit("--tls-cert", cert);
    options.pem_private_key = ReadFileOrExit("--tls-key", key);
  }
  return grpc::SslCredentials(options);
}

std::string BearerToken() {
  const std::string path = absl::GetFlag(FLAGS_token_file);
  if (path.empty()) {
    const char* env = std::getenv("APERTURE_TOKEN");
    return env == nullptr ? "" : std::string(absl::StripAsciiWhitespace(env));
  }
  std::istringstream lines(ReadFileOrExit("--token-file", path));
  std::string line;
  while (std::getline(lines, line)) {
    const std::string token(absl::StripAsciiWhitespace(line));
    if (!token.empty() && token.front() != '#') return token;
  }
  std::fprintf(stderr, "aperture: --token-file %s: no token in the file\n", path.c_str());
  std::exit(2);
}

std::shared_ptr<grpc::Channel> MakeChannel(const std::string& target, grpc::ChannelArguments args) {
  args.SetMaxReceiveMessageSize(-1);
  args.SetMaxSendMessageSize(-1);
  args.SetInt(GRPC_ARG_KEEPALIVE_TIME_MS, keepalive::kTimeMs);
  args.SetInt(GRPC_ARG_KEEPALIVE_TIMEOUT_MS, keepalive::kTimeoutMs);
  const std::string token = BearerToken();
  if (token.empty()) return grpc::CreateCustomChannel(target, ClientCredentials(), args);
  std::vector<std::unique_ptr<grpc::experimental::ClientInterceptorFactoryInterface>> interceptors;
  interceptors.push_back(std::make_unique<BearerTokenInterceptorFactory>(token));
  return grpc::experimental::CreateCustomChannelWithInterceptors(target, ClientCredentials(), args,
                                                                 std::move(interceptors));
}

std::shared_ptr<grpc::Channel> MakeChannel(const std::string& address) {
  return MakeChannel(address, grpc::ChannelArguments());
}

std::chrono::system_clock::time_point DeadlineIn(double seconds) {
  return std::chrono::system_clock::now() +
         std::chrono::microseconds(static_cast<int64_t>(seconds * 1e6));
}

}  // namespace aperture
