#include <google/protobuf/util/json_util.h>

#include <algorithm>
#include <cstdio>

#include "absl/flags/flag.h"
#include "aperture/v1/render_service.grpc.pb.h"
#include "channel.h"
#include "client_flags.h"
#include "commands.h"
#include "exit_status.h"
#include "grpc_status.h"

namespace aperture {

int RunInfo() {
  auto channel = ConnectChannel(absl::GetFlag(FLAGS_server));
  if (!channel.ok()) return Fail("info", channel.status());
  auto stub = v1::Render::NewStub(*channel);
  grpc::ClientContext context;
  context.set_deadline(DeadlineIn(std::min(absl::GetFlag(FLAGS_deadline_s), 10.0)));
  v1::GetServerInfoResponse response;
  if (absl::Status status =
          FromGrpcStatus(stub->GetServerInfo(&context, {}, &response), "GetServerInfo");
      !status.ok())
    return Fail("info", status);
  std::string json;
  google::protobuf::util::JsonPrintOptions options;
  options.add_whitespace = true;
  options.always_print_primitive_fields = true;
  (void)google::protobuf::util::MessageToJsonString(response, &json, options);
  std::printf("%s", json.c_str());
  return 0;
}

}  // namespace aperture
