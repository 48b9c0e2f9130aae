// absl::Status -> grpc::Status: the canonical codes are the same numbers in both libraries. The
// message goes back in the answer's trailers, which a client refuses past a few kilobytes (gRPC's
// metadata limit, 8 KiB by default; it then reports RESOURCE_EXHAUSTED of its own instead of the
// server's answer), so a message quoting a long client string is cut in its middle: the field it
// names and the reason, at its start and end, stay.
#pragma once

#include <grpcpp/support/status.h>

#include <string>

#include "absl/status/status.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/string_view.h"

namespace aperture {

inline constexpr size_t kMaxStatusMessageBytes = 1024;

inline std::string StatusMessageForClient(absl::string_view message) {
  if (message.size() <= kMaxStatusMessageBytes) return std::string(message);
  constexpr size_t kKeep = kMaxStatusMessageBytes / 2 - 32;
  return absl::StrCat(message.substr(0, kKeep), "...(", message.size() - 2 * kKeep,
                      " bytes cut)...", message.substr(message.size() - kKeep));
}

inline grpc::Status ToGrpcStatus(const absl::Status& status) {
  if (status.ok()) return grpc::Status::OK;
  return grpc::Status(static_cast<grpc::StatusCode>(status.code()),
                      StatusMessageForClient(status.message()));
}

}  // namespace aperture
