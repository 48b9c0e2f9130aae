// A channel to one server with the message limits raised for big frames (a 3840x2160 float
// frame is larger than gRPC's default 4 MiB receive limit), over TLS when --tls-ca is given.
#pragma once

#include <grpcpp/grpcpp.h>

#include <memory>
#include <string>

namespace aperture {

std::shared_ptr<grpc::Channel> MakeChannel(const std::string& address);

// TLS trusting --tls-ca when it is set, else plaintext. Exits with status 2 when the file cannot
// be read (a client that cannot start its channel has nothing else to do).
std::shared_ptr<grpc::ChannelCredentials> ClientCredentials();

// The deadline of a call `seconds` from now.
std::chrono::system_clock::time_point DeadlineIn(double seconds);

}  // namespace aperture
