#include "metrics_registry.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"

namespace aperture {
namespace {

// HELP text escapes backslash and line feed (not the double quote).
std::string EscapeHelp(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '\\')
      out += "\\\\";
    else if (c == '\n')
      out += "\\n";
    else
      out += c;
  }
  return out;
}

// {a="x",b="y"} with `extra` (le="0.5") last; empty when there are no labels at all.
std::string LabelText(const MetricsRegistry::Labels& names, const MetricsRegistry::Labels& values,
                      const std::string& extra = "") {
  std::string out;
  for (size_t i = 0; i < names.size() && i < values.size(); ++i)
    absl::StrAppend(&out, out.empty() ? "" : ",", names[i], "=\"", EscapeLabelValue(values[i]),
                    "\"");
  if (!extra.empty()) absl::StrAppend(&out, out.empty() ? "" : ",", extra);
  return out.empty() ? "" : absl::StrCat("{", out, "}");
}

}  // namespace

std::string MetricValueText(double value) {
  if (std::isnan(value)) return "NaN";
  if (std::isinf(value)) return value > 0 ? "+Inf" : "-Inf";
  if (value == std::floor(value) && std::abs(value) < 9007199254740992.0)  // 2^53
    return absl::StrFormat("%.0f", value);
  // The shortest form that reads back as the same double (0.033, not 0.033000000000000002).
  for (int digits = 15; digits < 17; ++digits) {
    const std::string text = absl::StrFormat("%.*g", digits, value);
    if (std::strtod(text.c_str(), nullptr) == value) return text;
  }
  return absl::StrFormat("%.17g", value);
}

std::string EscapeLabelValue(const std::string& value) {
  std::string out;
  for (char c : value) {
    if (c == '\\')
      out += "\\\\";
    else if (c == '"')
      out += "\\\"";
    else if (c == '\n')
      out += "\\n";
    else
      out += c;
  }
  return out;
}

void MetricsRegistry::Counter::Increment(const Labels& values, double by) {
  std::lock_guard lock(mutex_);
  series_[values] += by;
}

void MetricsRegistry::Histogram::Observe(const Labels& values, double value) {
  std::lock_guard lock(mutex_);
  Series& s = series_[values];
  if (s.counts.empty()) s.counts.assign(bounds_.size() + 1, 0);
  // The first bucket whose upper bound holds the value (le: less than or equal).
  const size_t bucket = std::lower_bound(bounds_.begin(), bounds_.end(), value) - bounds_.begin();
  ++s.counts[bucket];
  s.sum += value;
  ++s.count;
}

MetricsRegistry::Counter& MetricsRegistry::AddCounter(std::string name, std::string help,
                                                      Labels label_names) {
  auto family = std::make_unique<Family>();
  family->name = std::move(name);
  family->help = std::move(help);
  family->type = "counter";
  family->label_names = std::move(label_names);
  family->counter = std::make_unique<Counter>();
  Counter& counter = *family->counter;
  families_.push_back(std::move(family));
  return counter;
}

MetricsRegistry::Histogram& MetricsRegistry::AddHistogram(std::string name, std::string help,
                                                          Labels label_names,
                                                          std::vector<double> bounds) {
  auto family = std::make_unique<Family>();
  family->name = std::move(name);
  family->help = std::move(help);
  family->type = "histogram";
  family->label_names = std::move(label_names);
  std::sort(bounds.begin(), bounds.end());
  family->histogram.reset(new Histogram(std::move(bounds)));
  Histogram& histogram = *family->histogram;
  families_.push_back(std::move(family));
  return histogram;
}

void MetricsRegistry::AddGauge(std::string name, std::string help, std::function<double()> read) {
  auto family = std::make_unique<Family>();
  family->name = std::move(name);
  family->help = std::move(help);
  family->type = "gauge";
  family->read = std::move(read);
  families_.push_back(std::move(family));
}

void MetricsRegistry::AddCounterFunction(std::string name, std::string help,
                                         std::function<double()> read) {
  AddGauge(std::move(name), std::move(help), std::move(read));
  families_.back()->type = "counter";
}

std::string MetricsRegistry::Text() const {
  std::string out;
  for (const auto& f : families_) {
    absl::StrAppend(&out, "# HELP ", f->name, " ", EscapeHelp(f->help), "\n# TYPE ", f->name, " ",
                    f->type, "\n");
    if (f->read) {
      absl::StrAppend(&out, f->name, " ", MetricValueText(f->read()), "\n");
    } else if (f->counter) {
      std::lock_guard lock(f->counter->mutex_);
      for (const auto& [values, value] : f->counter->series_)
        absl::StrAppend(&out, f->name, LabelText(f->label_names, values), " ",
                        MetricValueText(value), "\n");
    } else if (f->histogram) {
      const Histogram& h = *f->histogram;
      std::lock_guard lock(f->histogram->mutex_);
      for (const auto& [values, s] : h.series_) {
        uint64_t cumulative = 0;
        for (size_t b = 0; b <= h.bounds_.size(); ++b) {
          cumulative += s.counts[b];
          const std::string le =
              b < h.bounds_.size() ? MetricValueText(h.bounds_[b]) : std::string("+Inf");
          absl::StrAppend(&out, f->name, "_bucket",
                          LabelText(f->label_names, values, absl::StrCat("le=\"", le, "\"")), " ",
                          cumulative, "\n");
        }
        absl::StrAppend(&out, f->name, "_sum", LabelText(f->label_names, values), " ",
                        MetricValueText(s.sum), "\n", f->name, "_count",
                        LabelText(f->label_names, values), " ", s.count, "\n");
      }
    }
  }
  return out;
}

}  // namespace aperture
