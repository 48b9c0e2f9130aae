#include "metrics_http.h"

#include <httplib.h>

#include <chrono>

#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"

namespace aperture {
namespace {

struct HostPort {
  std::string host;  // without an IPv6 address's brackets
  int port = 0;
};

absl::StatusOr<HostPort> ParseAddress(const std::string& address) {
  const size_t colon = address.rfind(':');
  auto invalid = [&] {
    return absl::InvalidArgumentError(absl::StrCat(
        "--metrics-listen '", address, "' is not HOST:PORT (e.g. 127.0.0.1:9464, [::1]:9464)"));
  };
  if (colon == std::string::npos || colon == 0) return invalid();
  HostPort out;
  out.host = address.substr(0, colon);
  if (out.host.front() == '[') {
    if (out.host.size() < 3 || out.host.back() != ']') return invalid();
    out.host = out.host.substr(1, out.host.size() - 2);
  }
  if (!absl::SimpleAtoi(address.substr(colon + 1), &out.port) || out.port < 0 || out.port > 65535)
    return invalid();
  return out;
}

}  // namespace

absl::StatusOr<std::unique_ptr<MetricsHttpServer>> MetricsHttpServer::Start(
    const std::string& address, const ServiceMetrics& metrics) {
  auto parsed = ParseAddress(address);
  if (!parsed.ok()) return parsed.status();
  std::unique_ptr<MetricsHttpServer> server(new MetricsHttpServer);
  server->server_ = std::make_unique<httplib::Server>();
  httplib::Server& http = *server->server_;
  // A scrape is one small GET: two threads, short timeouts, no bodies.
  http.new_task_queue = [] { return new httplib::ThreadPool(2); };
  http.set_read_timeout(5);
  http.set_write_timeout(5);
  http.set_keep_alive_max_count(100);
  http.set_payload_max_length(0);
  http.Get(kPath, [&metrics](const httplib::Request&, httplib::Response& response) {
    response.set_content(metrics.Text(), "text/plain; version=0.0.4; charset=utf-8");
  });
  const HostPort& where = *parsed;
  int port = where.port;
  const bool bound = port == 0 ? (port = http.bind_to_any_port(where.host)) > 0
                               : http.bind_to_port(where.host, port);
  if (!bound)
    return absl::UnavailableError(absl::StrCat("--metrics-listen ", address, ": cannot listen"));
  server->address_ = where.host.find(':') != std::string::npos
                         ? absl::StrCat("[", where.host, "]:", port)
                         : absl::StrCat(where.host, ":", port);
  server->thread_ = std::thread([&http] { http.listen_after_bind(); });
  // Running before it is returned: a stop() before the loop starts would be lost, and the
  // destructor's join would wait for ever.
  for (int i = 0; i < 2000 && !http.is_running(); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  return server;
}

MetricsHttpServer::~MetricsHttpServer() {
  if (server_) server_->stop();
  if (thread_.joinable()) thread_.join();
}

}  // namespace aperture
