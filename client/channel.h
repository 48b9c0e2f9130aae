// A channel to one server with the message limits raised for big frames (a 3840x2160 float
// frame is larger than gRPC's default 4 MiB receive limit), over TLS when --tls-ca is given
// (with this client's certificate when --tls-cert is), and with the bearer token of
// --token-file or APERTURE_TOKEN on every call when one is given. Nothing here exits: errors are
// statuses the commands turn into a message and an exit status (exit_status.h).
#pragma once

#include <grpcpp/grpcpp.h>

#include <memory>
#include <string>

#include "absl/status/statusor.h"

namespace aperture {

// An input error (INVALID_ARGUMENT naming the flag and the file) when --tls-ca, --tls-cert,
// --tls-key or --token-file cannot be used. The channel connects on its first call.
absl::StatusOr<std::shared_ptr<grpc::Channel>> MakeChannel(
    const std::string& target, grpc::ChannelArguments args = grpc::ChannelArguments());

// MakeChannel, then connected: the server at `address` has answered (TCP, and TLS when used)
// within `timeout_s` seconds (at most --deadline-s). An input error (UNAVAILABLE) naming the
// address and gRPC's reason when the name does not resolve or nothing answers there.
absl::StatusOr<std::shared_ptr<grpc::Channel>> ConnectChannel(const std::string& address,
                                                              double timeout_s = 10);

// TLS trusting --tls-ca when it is set, else plaintext; an input error when a file cannot be
// read or the flags do not go together.
absl::StatusOr<std::shared_ptr<grpc::ChannelCredentials>> ClientCredentials();

// The bearer token: the first line of --token-file, else APERTURE_TOKEN, else empty; an input
// error when --token-file cannot be read or holds no token.
absl::StatusOr<std::string> BearerToken();

// The deadline of a call `seconds` from now.
std::chrono::system_clock::time_point DeadlineIn(double seconds);

}  // namespace aperture
