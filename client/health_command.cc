#include <cstdio>

#include "absl/flags/flag.h"
#include "channel.h"
#include "client_flags.h"
#include "commands.h"
#include "grpc/health/v1/health.grpc.pb.h"

namespace aperture {

int RunHealth() {
  auto stub = grpc::health::v1::Health::NewStub(MakeChannel(absl::GetFlag(FLAGS_server)));
  grpc::ClientContext context;
  context.set_deadline(DeadlineIn(std::min(absl::GetFlag(FLAGS_deadline_s), 5.0)));
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
