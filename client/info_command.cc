#include <google/protobuf/util/json_util.h>

#include <cstdio>

#include "absl/flags/flag.h"
#include "aperture/v1/render_service.grpc.pb.h"
#include "channel.h"
#include "client_flags.h"
#include "commands.h"
#include "grpc_status.h"

namespace aperture {

int RunInfo() {
  auto stub = v1::Render::NewStub(MakeChannel(absl::GetFlag(FLAGS_server)));
  grpc::ClientContext context;
  context.set_deadline(DeadlineIn(10));
  v1::GetServerInfoResponse response;
  const grpc::Status status = stub->GetServerInfo(&context, {}, &response);
  if (!status.ok()) {
    std::fprintf(stderr, "aperture info: %s\n", status.error_message().c_str());
    return 1;
  }
  std::string json;
  google::protobuf::util::JsonPrintOptions options;
  options.add_whitespace = true;
  options.always_print_primitive_fields = true;
  (void)google::protobuf::util::MessageToJsonString(response, &json, options);
  std::printf("%s", json.c_str());
  return 0;
}

}  // namespace aperture
