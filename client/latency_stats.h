// Latency percentiles of a set of samples (milliseconds), nearest-rank.
#pragma once

#include <cstddef>
#include <vector>

namespace aperture {

struct LatencySummary {
  size_t count = 0;
  double p50 = 0, p90 = 0, p99 = 0, max = 0, mean = 0;
};

LatencySummary Summarize(std::vector<double> samples_ms);

}  // namespace aperture
