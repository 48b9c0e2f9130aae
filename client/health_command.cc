#include <algorithm>
#include <cstdio>

#include "absl/flags/flag.h"
#include "channel.h"
#include "client_flags.h"
#include "commands.h"
#include "exit_status.h"
#include "grpc/health/v1/health.grpc.pb.h"

namespace aperture {

int RunHealth() {
  // A probe's answer: a server that cannot be reached is not healthy (1, as Docker's HEALTHCHECK
  // and other probes read it; they reserve 2); a flag or file that cannot be used is bad input.
  const double timeout_s = std::min(absl::GetFlag(FLAGS_deadline_s), 5.0);
  auto channel = ConnectChannel(absl::GetFlag(FLAGS_server), timeout_s);
  if (!channel.ok()) {
    Fail("health", channel.status());
    return absl::IsUnavailable(channel.status()) ? 1 : 2;
  }
  auto stub = grpc::health::v1::Health::NewStub(*channel);
  grpc::ClientContext context;
  context.set_deadline(DeadlineIn(timeout_s));
  grpc::health::v1::HealthCheckRequest request;
  grpc::health::v1::HealthCheckResponse response;
  const grpc::Status status = stub->Check(&context, request, &response);
  if (!status.ok()) {
    std::fprintf(stderr, "aperture health: %s: %s\n", absl::GetFlag(FLAGS_server).c_str(),
                 status.error_message().c_str());
    return 1;
  }
  std::printf("%s\n",
              grpc::health::v1::HealthCheckResponse::ServingStatus_Name(response.status()).c_str());
  return response.status() == grpc::health::v1::HealthCheckResponse::SERVING ? 0 : 1;
}

}  // namespace aperture
