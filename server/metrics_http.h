// The HTTP endpoint of --metrics-listen: GET /metrics answers the text exposition format of a
// ServiceMetrics (HEAD too); every other path and method answers 404. Served by Debian's
// cpp-httplib on two threads of its own, apart from the render arena and gRPC's threads, with
// short timeouts and no request bodies, so a slow or hostile scraper holds little.
#pragma once

#include <memory>
#include <string>
#include <thread>

#include "absl/status/statusor.h"
#include "service_metrics.h"

namespace httplib {
class Server;
}

namespace aperture {

class MetricsHttpServer {
 public:
  static constexpr const char* kPath = "/metrics";

  // Listens on `address` (HOST:PORT, [IPV6]:PORT; port 0: any free port) and serves until
  // destroyed. INVALID_ARGUMENT for an address that is not HOST:PORT, UNAVAILABLE when it cannot
  // be bound. `metrics` must outlive the server.
  static absl::StatusOr<std::unique_ptr<MetricsHttpServer>> Start(const std::string& address,
                                                                  const ServiceMetrics& metrics);
  ~MetricsHttpServer();  // stops serving and joins its threads
  MetricsHttpServer(const MetricsHttpServer&) = delete;
  MetricsHttpServer& operator=(const MetricsHttpServer&) = delete;

  // HOST:PORT as bound (the port chosen when 0 was asked).
  const std::string& address() const { return address_; }

 private:
  MetricsHttpServer() = default;
  std::unique_ptr<httplib::Server> server_;
  std::thread thread_;
  std::string address_;
};

}  // namespace aperture
