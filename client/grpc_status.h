// grpc::Status -> absl::Status (the canonical codes are the same numbers), with the RPC named.
#pragma once

#include <grpcpp/support/status.h>

#include <string>

#include "absl/status/status.h"
#include "absl/strings/str_cat.h"

namespace aperture {

inline absl::Status FromGrpcStatus(const grpc::Status& status, const std::string& rpc) {
  if (status.ok()) return absl::OkStatus();
  return absl::Status(static_cast<absl::StatusCode>(status.error_code()),
                      absl::StrCat(rpc, ": ", status.error_message()));
}

// "INVALID_ARGUMENT", ...: absl's name of the same code.
inline std::string GrpcCodeName(grpc::StatusCode code) {
  return absl::StatusCodeToString(static_cast<absl::StatusCode>(code));
}

// Whether another attempt (maybe on another server) can succeed: the server was busy, gone or
// too slow. A request it refused (INVALID_ARGUMENT, NOT_FOUND, UNAUTHENTICATED, ...) is refused
// the same way everywhere.
inline bool Retryable(grpc::StatusCode code) {
  switch (code) {
    case grpc::StatusCode::UNAVAILABLE:
    case grpc::StatusCode::RESOURCE_EXHAUSTED:
    case grpc::StatusCode::DEADLINE_EXCEEDED:
    case grpc::StatusCode::ABORTED:
    case grpc::StatusCode::CANCELLED:
    case grpc::StatusCode::UNKNOWN:
    case grpc::StatusCode::INTERNAL:
      return true;
    default:
      return false;
  }
}

}  // namespace aperture
