// Log lines for refused requests, at most one per interval (a second) for each kind of refusal: a
// client that retries a refused request at once would otherwise write a line per attempt,
// megabytes of log a second. A line counts the refusals of its kind since the kind's previous
// line and quotes the latest of them:
//   refused 812 frames in the last 1.0 s: queue full; the latest: req=... error='server busy: ...'
// (or `refused 1 frame: queue full; req=...` for a refusal alone).
// The first refusal of a kind after a quiet interval is written at once; those that follow within
// the interval are counted, and written by the first refusal after it or by Flush, which a
// flushing thread (StartFlushing) calls four times an interval so that a burst's tail is not
// held back (it is written at most 1.25 intervals after its kind's last line).
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "absl/status/status.h"
#include "absl/strings/string_view.h"

namespace aperture {

class RefusalLog {
 public:
  using Clock = std::chrono::steady_clock;
  using Sink = std::function<void(const std::string& line)>;

  explicit RefusalLog(Sink sink, Clock::duration interval = std::chrono::seconds(1));
  ~RefusalLog();  // writes what is still counted
  RefusalLog(const RefusalLog&) = delete;
  RefusalLog& operator=(const RefusalLog&) = delete;

  // One refusal of `kind` ("queue full") of a `thing` ("frame": the line counts "frames");
  // `latest` says what this one was, quoted if its line is written before another comes.
  void Refused(absl::string_view kind, absl::string_view thing, std::string latest,
               Clock::time_point now = Clock::now());
  // Writes the counts of the kinds whose interval has passed since their last line; with `all`,
  // every count not yet written.
  void Flush(Clock::time_point now = Clock::now(), bool all = false);
  // Calls Flush four times an interval on a thread of its own, until the log is destroyed.
  void StartFlushing();

 private:
  struct Kind {
    std::string kind, thing;
    uint64_t pending = 0;                   // refusals counted since the last line
    std::string latest;                     // the latest of them
    std::optional<Clock::time_point> last;  // of the last line
  };
  // Whether `k`'s count is due at `now`: no line yet, or the last an interval ago.
  bool Due(const Kind& k, Clock::time_point now) const;
  // The line for `k`'s pending refusals, which it resets.
  static std::string Line(Kind& k, Clock::time_point now);

  const Sink sink_;
  const Clock::duration interval_;
  std::mutex mutex_;
  std::map<std::string, Kind, std::less<>> kinds_;  // by kind and thing
  std::jthread flusher_;                            // last: stopped before the rest goes
};

// A request refused for capacity carries its kind of refusal ("queue full", "over the loaded
// scenes' budget (--max-scenes-mb)") in its status, so that the request's log line goes to a
// RefusalLog rather than to the log directly.
absl::Status MarkRefusal(absl::Status status, absl::string_view kind);
// The kind MarkRefusal gave, if any.
std::optional<std::string> RefusalKind(const absl::Status& status);

// The kinds the server marks.
inline constexpr absl::string_view kQueueFullRefusal = "queue full";
inline constexpr absl::string_view kStoreBudgetRefusal = "over the texture store's budget";

}  // namespace aperture
