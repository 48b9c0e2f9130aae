// Counters, histograms and gauges in the Prometheus text exposition format (version 0.0.4), for
// aperture-server --metrics-listen. Debian has no Prometheus client library for C++ (no
// prometheus-cpp in bookworm), and the format is small: each family a HELP and a TYPE line, then
// its series; a histogram's buckets cumulative, ending at le="+Inf", with _sum and _count.
// Counters and histograms are kept here, updated from any thread; gauges and counters the server
// keeps itself (a store's bytes, its evictions) are read when the text is made.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace aperture {

class MetricsRegistry {
 public:
  using Labels = std::vector<std::string>;  // values, in the order of the family's label names

  class Counter {
   public:
    void Increment(const Labels& values, double by = 1);

   private:
    friend class MetricsRegistry;
    std::mutex mutex_;
    std::map<Labels, double> series_;
  };

  class Histogram {
   public:
    void Observe(const Labels& values, double value);

   private:
    friend class MetricsRegistry;
    struct Series {
      std::vector<uint64_t> counts;  // per bucket, not cumulative; one more for +Inf
      double sum = 0;
      uint64_t count = 0;
    };
    explicit Histogram(std::vector<double> bounds) : bounds_(std::move(bounds)) {}
    const std::vector<double> bounds_;  // upper bounds, increasing
    std::mutex mutex_;
    std::map<Labels, Series> series_;
  };

  // Names follow Prometheus' conventions (a counter's ends in _total, a unit's in _seconds or
  // _bytes); the registry keeps the order families were added in. The references stay valid for
  // the registry's life.
  Counter& AddCounter(std::string name, std::string help, Labels label_names);
  Histogram& AddHistogram(std::string name, std::string help, Labels label_names,
                          std::vector<double> bounds);
  // Read when the text is made: a value that goes up and down, or a count kept elsewhere.
  void AddGauge(std::string name, std::string help, std::function<double()> read);
  void AddCounterFunction(std::string name, std::string help, std::function<double()> read);

  // Every family in the text exposition format.
  std::string Text() const;

 private:
  struct Family {
    std::string name, help, type;
    Labels label_names;
    std::unique_ptr<Counter> counter;
    std::unique_ptr<Histogram> histogram;
    std::function<double()> read;  // a gauge or a counter kept elsewhere
  };
  std::vector<std::unique_ptr<Family>> families_;
};

// A sample's value as the format writes it: integers exactly, +Inf, NaN, else shortest round trip.
std::string MetricValueText(double value);
// A label value with backslash, double quote and line feed escaped.
std::string EscapeLabelValue(const std::string& value);

}  // namespace aperture
