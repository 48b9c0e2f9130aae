// A channel to one server with the message limits raised for big frames (a 3840x2160 float
// frame is larger than gRPC's default 4 MiB receive limit), over TLS when --tls-ca is given
// (with this client's certificate when --tls-cert is), and with the bearer token of
// --token-file or APERTURE_TOKEN on every call when one is given.
#pragma once

#include <grpcpp/grpcpp.h>

#include <memory>
#include <string>

namespace aperture {

std::shared_ptr<grpc::Channel> MakeChannel(const std::string& address);
// The same with the caller's channel arguments (a load-balancing policy, say).
std::shared_ptr<grpc::Channel> MakeChannel(const std::string& target, grpc::ChannelArguments args);

// TLS trusting --tls-ca when it is set, else plaintext. Exits with status 2 when a file cannot
// be read (a client that cannot start its channel has nothing else to do).
std::shared_ptr<grpc::ChannelCredentials> ClientCredentials();

// The bearer token: the first line of --token-file, else APERTURE_TOKEN, else empty. Exits with
// status 2 when --token-file cannot be read or holds no token.
std::string BearerToken();

// The deadline of a call `seconds` from now.
std::chrono::system_clock::time_point DeadlineIn(double seconds);

}  // namespace aperture
