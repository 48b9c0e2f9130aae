#include "sim_compression.h"

#include <algorithm>

#include "absl/strings/match.h"
#include "absl/strings/strip.h"

namespace aperture {

bool IsLoopbackTarget(absl::string_view target) {
  if (absl::StartsWith(target, "unix:") || absl::StartsWith(target, "unix-abstract:")) return true;
  // gRPC's name schemes: dns:[//authority/]host[:port], ipv4:address[:port],
  // ipv6:[address][:port].
  if (absl::ConsumePrefix(&target, "dns:")) {
    if (absl::ConsumePrefix(&target, "//"))
      target.remove_prefix(std::min(target.find('/'), target.size()));
    absl::ConsumePrefix(&target, "/");
  } else if (!absl::ConsumePrefix(&target, "ipv4:")) {
    absl::ConsumePrefix(&target, "ipv6:");
  }
  absl::string_view host = target;
  if (absl::StartsWith(host, "[")) {
    const size_t close = host.find(']');
    if (close == absl::string_view::npos) return false;
    host = host.substr(1, close - 1);
  } else if (const size_t colon = host.rfind(':');
             colon != absl::string_view::npos && host.find(':') == colon) {
    host = host.substr(0, colon);  // host:port (a bare IPv6 address has more than one colon)
  }
  return host == "localhost" || host == "::1" || absl::StartsWith(host, "127.");
}

v1::ExrCompression SimDefaultCompression(absl::string_view target, v1::PixelType pixel_type) {
  return IsLoopbackTarget(target) || pixel_type == v1::PIXEL_TYPE_FLOAT ? v1::EXR_COMPRESSION_ZIP
                                                                        : v1::EXR_COMPRESSION_B44A;
}

}  // namespace aperture
