#include "channel.h"

#include <grpcpp/support/client_interceptor.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "absl/flags/flag.h"
#include "absl/strings/ascii.h"
#include "absl/strings/str_cat.h"
#include "client_flags.h"
#include "exit_status.h"
#include "grpc/health/v1/health.grpc.pb.h"
#include "keepalive.h"

namespace aperture {
namespace {

absl::StatusOr<std::string> ReadFlagFile(const std::string& flag, const std::string& path) {
  std::ifstream in(path);
  std::ostringstream content;
  content << in.rdbuf();
  if (!in || content.str().empty())
    return InputError(
        absl::InvalidArgumentError(absl::StrCat(flag, " ", path, ": cannot read the file")));
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

// Why a channel did not connect, in gRPC's words ("DNS resolution failed for ...", "failed to
// connect to all addresses; ... Connection refused"): a call that fails fast says it.
std::string WhyNotConnected(const std::shared_ptr<grpc::Channel>& channel) {
  auto stub = grpc::health::v1::Health::NewStub(channel);
  grpc::ClientContext context;
  context.set_deadline(DeadlineIn(1));
  grpc::health::v1::HealthCheckResponse response;
  const grpc::Status status = stub->Check(&context, {}, &response);
  return status.ok() ? "no connection" : status.error_message();
}

}  // namespace

absl::StatusOr<std::shared_ptr<grpc::ChannelCredentials>> ClientCredentials() {
  const std::string ca = absl::GetFlag(FLAGS_tls_ca);
  const std::string cert = absl::GetFlag(FLAGS_tls_cert), key = absl::GetFlag(FLAGS_tls_key);
  if (ca.empty()) {
    if (!cert.empty() || !key.empty())
      return InputError(absl::InvalidArgumentError("--tls-cert and --tls-key need --tls-ca (TLS)"));
    return grpc::InsecureChannelCredentials();
  }
  if (cert.empty() != key.empty())
    return InputError(absl::InvalidArgumentError("--tls-cert and --tls-key go together"));
  grpc::SslCredentialsOptions options;
  auto root = ReadFlagFile("--tls-ca", ca);
  if (!root.ok()) return root.status();
  options.pem_root_certs = *std::move(root);
  if (!cert.empty()) {
    auto chain = ReadFlagFile("--tls-cert", cert);
    if (!chain.ok()) return chain.status();
    auto private_key = ReadFlagFile("--tls-key", key);
    if (!private_key.ok()) return private_key.status();
    options.pem_cert_chain = *std::move(chain);
    options.pem_private_key = *std::move(private_key);
  }
  return grpc::SslCredentials(options);
}

absl::StatusOr<std::string> BearerToken() {
  const std::string path = absl::GetFlag(FLAGS_token_file);
  if (path.empty()) {
    const char* env = std::getenv("APERTURE_TOKEN");
    return env == nullptr ? "" : std::string(absl::StripAsciiWhitespace(env));
  }
  auto content = ReadFlagFile("--token-file", path);
  if (!content.ok()) return content.status();
  std::istringstream lines(*content);
  std::string line;
  while (std::getline(lines, line)) {
    const std::string token(absl::StripAsciiWhitespace(line));
    if (!token.empty() && token.front() != '#') return token;
  }
  return InputError(
      absl::InvalidArgumentError(absl::StrCat("--token-file ", path, ": no token in the file")));
}

absl::StatusOr<std::shared_ptr<grpc::Channel>> MakeChannel(const std::string& target,
                                                           grpc::ChannelArguments args) {
  args.SetMaxReceiveMessageSize(-1);
  args.SetMaxSendMessageSize(-1);
  args.SetInt(GRPC_ARG_KEEPALIVE_TIME_MS, keepalive::kTimeMs);
  args.SetInt(GRPC_ARG_KEEPALIVE_TIMEOUT_MS, keepalive::kTimeoutMs);
  auto credentials = ClientCredentials();
  if (!credentials.ok()) return credentials.status();
  auto token = BearerToken();
  if (!token.ok()) return token.status();
  if (token->empty()) return grpc::CreateCustomChannel(target, *credentials, args);
  std::vector<std::unique_ptr<grpc::experimental::ClientInterceptorFactoryInterface>> interceptors;
  interceptors.push_back(std::make_unique<BearerTokenInterceptorFactory>(*token));
  return grpc::experimental::CreateCustomChannelWithInterceptors(target, *credentials, args,
                                                                 std::move(interceptors));
}

absl::StatusOr<std::shared_ptr<grpc::Channel>> ConnectChannel(const std::string& address,
                                                              double timeout_s) {
  auto channel = MakeChannel(address);
  if (!channel.ok()) return channel.status();
  const auto deadline = DeadlineIn(std::min(timeout_s, absl::GetFlag(FLAGS_deadline_s)));
  // The first attempt decides: a name that does not resolve, a refused connection or a failed
  // handshake turn the channel to TRANSIENT_FAILURE (gRPC would go on retrying with backoff).
  for (grpc_connectivity_state state = (*channel)->GetState(/*try_to_connect=*/true);
       state != GRPC_CHANNEL_READY; state = (*channel)->GetState(/*try_to_connect=*/true)) {
    if (state == GRPC_CHANNEL_TRANSIENT_FAILURE || state == GRPC_CHANNEL_SHUTDOWN ||
        !(*channel)->WaitForStateChange(state, deadline))
      return InputError(absl::UnavailableError(
          absl::StrCat("cannot reach a server at ", address, ": ",
                       state == GRPC_CHANNEL_TRANSIENT_FAILURE ? WhyNotConnected(*channel)
                                                               : "no answer before the deadline")));
  }
  return channel;
}

std::chrono::system_clock::time_point DeadlineIn(double seconds) {
  return std::chrono::system_clock::now() +
         std::chrono::microseconds(static_cast<int64_t>(seconds * 1e6));
}

}  // namespace aperture
