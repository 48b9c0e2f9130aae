#include "rpc_calls.h"

#include <spdlog/fmt/fmt.h>
#include <spdlog/spdlog.h>

#include "log_text.h"
#include "status_mapping.h"

namespace aperture {

RpcCalls::RpcCalls(const AuthTokens* auth)
    : auth_(auth),
      refusals_([](const std::string& line) { spdlog::info("{}", line); }),
      auth_refusals_([](const std::string& line) { spdlog::warn("{}", line); }) {
  refusals_.StartFlushing();
  auth_refusals_.StartFlushing();
}

absl::Status RpcCalls::Authorize(const grpc::ServerContext& context, const char* rpc) {
  if (auth_ == nullptr) return absl::OkStatus();
  absl::Status status = auth_->Check(context);
  if (!status.ok())
    auth_refusals_.Refused("unauthenticated", "call",
                           fmt::format("rpc={} peer={} status=UNAUTHENTICATED error='{}'", rpc,
                                       context.peer(), LogText(status.message())));
  return status;
}

void RpcCalls::Log(const absl::Status& status, absl::string_view thing, std::string line) {
  if (auto kind = RefusalKind(status); kind && absl::IsResourceExhausted(status)) {
    // A client that retries at once must not get a line per attempt. (A frame that worked and
    // then passed its memory budget is logged as every frame is.)
    refusals_.Refused(*kind, thing, std::move(line));
    return;
  }
  spdlog::info("{}", line);
}

grpc::Status RpcCalls::Logged(grpc::ServerContext* context, const char* rpc,
                              absl::string_view thing,
                              absl::FunctionRef<absl::Status(RpcCall&)> body) {
  if (absl::Status auth = Authorize(*context, rpc); !auth.ok()) return ToGrpcStatus(auth);
  RpcCall call;
  call.id = next_id_++;
  call.start = RpcCall::Clock::now();
  const absl::Status status = body(call);
  Log(status, thing,
      fmt::format(
          "req={} rpc={} peer={} {} status={}{}", call.id, rpc, context->peer(), call.fields,
          absl::StatusCodeToString(status.code()),
          status.message().empty() ? "" : fmt::format(" error='{}'", LogText(status.message()))));
  return ToGrpcStatus(status);
}

grpc::Status RpcCalls::Quiet(grpc::ServerContext* context, const char* rpc,
                             absl::FunctionRef<absl::Status()> body) {
  if (absl::Status auth = Authorize(*context, rpc); !auth.ok()) return ToGrpcStatus(auth);
  return ToGrpcStatus(body());
}

}  // namespace aperture
