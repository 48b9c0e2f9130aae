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

}  // namespace aperture
