// Printing the --json reports of `aperture load` and `aperture sim` (client_reports.proto) with
// protobuf's JSON printer.
#pragma once

#include <google/protobuf/message.h>

#include <string>

#include "aperture/v1/client_reports.pb.h"
#include "latency_stats.h"
#include "transport_delay.h"

namespace aperture {

// A figure kept to 3 decimals: milliseconds to the microsecond, rates to 1/1000.
double Rounded(double value);

v1::LatencyMs LatencyReport(const LatencySummary& s);

v1::TransportDelayMs TransportDelayReport(const TransportDelay& t);

// One line of JSON (no newline): field names as in the proto, every field present.
std::string ReportJson(const google::protobuf::Message& report);

}  // namespace aperture
