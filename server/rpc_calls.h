// What every RPC of the Render service does around its own work, written once: the caller's
// bearer token is checked before any work (UNAUTHENTICATED; the refusal logged with the peer,
// never the token, at most a line a second), the call is given a request id and a clock, and its
// one log line is written as it ends:
//
//   req=ID rpc=NAME peer=PEER <the call's own fields> status=CODE error='MESSAGE'
//
// (error only when there is a message). A refusal (RESOURCE_EXHAUSTED marked with its kind,
// refusal_log.h) goes to the refusal log, counted by kind, so a client retrying at once does not
// get a line per attempt.
//
// Why not a gRPC server interceptor: gRPC C++'s server interceptors cannot end a call before its
// handler runs (only client interceptors may hijack one), so a refused token would still reach
// the handler; and AuthMetadataProcessor does not run on a plaintext listener, which loopback
// deployments use with tokens.
#pragma once

#include <grpcpp/server_context.h>
#include <grpcpp/support/status.h>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <string>

#include "absl/functional/function_ref.h"
#include "absl/status/status.h"
#include "absl/strings/string_view.h"
#include "auth_tokens.h"
#include "refusal_log.h"

namespace aperture {

// One call as its handler sees it.
struct RpcCall {
  using Clock = std::chrono::steady_clock;
  uint64_t id = 0;          // the log line's req=
  Clock::time_point start;  // when the call was let in
  std::string fields;       // the line's own part, after peer= ("scene=... ms=12.34")
  double Milliseconds() const {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
  }
};

class RpcCalls {
 public:
  explicit RpcCalls(const AuthTokens* auth);  // null: no authentication

  // Checks the token, runs `body`, writes the call's line (its refusals counted as `thing`s:
  // "frame", "upload") and returns the body's status for gRPC.
  grpc::Status Logged(grpc::ServerContext* context, const char* rpc, absl::string_view thing,
                      absl::FunctionRef<absl::Status(RpcCall&)> body);
  // Checks the token and runs `body`, with no line and no request id: the calls a client may
  // make every second (HasTexture before each upload, GetServerInfo as a monitor's poll).
  grpc::Status Quiet(grpc::ServerContext* context, const char* rpc,
                     absl::FunctionRef<absl::Status()> body);

  // A line of a call's own besides its last (a stream's frames), routed as Logged routes its
  // line: to the refusal log when `status` is a refusal of a `thing`.
  void Log(const absl::Status& status, absl::string_view thing, std::string line);

 private:
  // OK, or UNAUTHENTICATED (logged) when tokens are required and the call has none accepted.
  absl::Status Authorize(const grpc::ServerContext& context, const char* rpc);

  const AuthTokens* const auth_;
  std::atomic<uint64_t> next_id_{1};
  RefusalLog refusals_;       // RESOURCE_EXHAUSTED, at info level
  RefusalLog auth_refusals_;  // UNAUTHENTICATED, at warn level
};

}  // namespace aperture
