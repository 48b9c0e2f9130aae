#include "report_json.h"

#include <google/protobuf/util/json_util.h>

#include <cmath>

namespace aperture {

double Rounded(double value) { return std::round(value * 1000) / 1000; }

v1::LatencyMs LatencyReport(const LatencySummary& s) {
  v1::LatencyMs out;
  out.set_p50(Rounded(s.p50));
  out.set_p90(Rounded(s.p90));
  out.set_p99(Rounded(s.p99));
  out.set_max(Rounded(s.max));
  out.set_mean(Rounded(s.mean));
  return out;
}

v1::TransportDelayMs TransportDelayReport(const TransportDelay& t) {
  v1::TransportDelayMs out;
  out.set_p50(Rounded(t.delay_ms.p50));
  out.set_p99(Rounded(t.delay_ms.p99));
  out.set_max(Rounded(t.delay_ms.max));
  out.set_request(Rounded(t.request_ms));
  out.set_wait(Rounded(t.wait_ms));
  out.set_render(Rounded(t.render_ms));
  out.set_hold(Rounded(t.hold_ms));
  out.set_encode(Rounded(t.encode_ms));
  out.set_send(Rounded(t.send_ms));
  out.set_unordered(static_cast<uint32_t>(t.unordered));
  return out;
}

std::string ReportJson(const google::protobuf::Message& report) {
  google::protobuf::util::JsonPrintOptions options;
  options.always_print_primitive_fields = true;
  options.preserve_proto_field_names = true;
  std::string out;
  // The report messages hold numbers, strings, maps and lists only: always convertible.
  (void)google::protobuf::util::MessageToJsonString(report, &out, options);
  return out;
}

}  // namespace aperture
