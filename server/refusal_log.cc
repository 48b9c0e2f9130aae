#include "refusal_log.h"

#include <condition_variable>
#include <vector>

#include "absl/strings/cord.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"

namespace aperture {
namespace {

// The payload MarkRefusal sets: a type URL of this server's own.
constexpr absl::string_view kRefusalKindUrl = "type.aperture.dev/server.RefusalKind";

}  // namespace

RefusalLog::RefusalLog(Sink sink, Clock::duration interval)
    : sink_(std::move(sink)), interval_(interval) {}

RefusalLog::~RefusalLog() {
  if (flusher_.joinable()) {
    flusher_.request_stop();
    flusher_.join();
  }
  Flush(Clock::now(), /*all=*/true);
}

bool RefusalLog::Due(const Kind& k, Clock::time_point now) const {
  return !k.last || now - *k.last >= interval_;
}

std::string RefusalLog::Line(Kind& k, Clock::time_point now) {
  std::string line =
      k.pending == 1
          ? absl::StrCat("refused 1 ", k.thing, ": ", k.kind, "; ", k.latest)
          : absl::StrFormat("refused %u %ss in the last %.1f s: %s; the latest: %s", k.pending,
                            k.thing, std::chrono::duration<double>(now - *k.last).count(), k.kind,
                            k.latest);
  k.pending = 0;
  k.latest.clear();
  k.last = now;
  return line;
}

void RefusalLog::Refused(absl::string_view kind, absl::string_view thing, std::string latest,
                         Clock::time_point now) {
  std::string line;
  {
    std::lock_guard lock(mutex_);
    const std::string key = absl::StrCat(kind, "\n", thing);
    auto it = kinds_.find(key);
    if (it == kinds_.end())
      it = kinds_.emplace(key, Kind{std::string(kind), std::string(thing)}).first;
    Kind& k = it->second;
    ++k.pending;
    k.latest = std::move(latest);
    if (Due(k, now)) line = Line(k, now);
  }
  if (!line.empty()) sink_(line);  // outside the lock: the sink may be slow
}

void RefusalLog::Flush(Clock::time_point now, bool all) {
  std::vector<std::string> lines;
  {
    std::lock_guard lock(mutex_);
    for (auto& [key, k] : kinds_)
      if (k.pending > 0 && (all || Due(k, now))) lines.push_back(Line(k, now));
  }
  for (const std::string& line : lines) sink_(line);
}

void RefusalLog::StartFlushing() {
  flusher_ = std::jthread([this](std::stop_token stop) {
    std::mutex mutex;
    std::condition_variable_any wake;
    std::unique_lock lock(mutex);
    // Four looks an interval: a tail comes due an interval after its kind's last line, whatever
    // the thread's phase, and is written within a quarter interval of that (every interval, a
    // tail due just after a look waited almost two).
    while (!wake.wait_for(lock, stop, interval_ / 4, [&] { return stop.stop_requested(); }))
      Flush();
  });
}

absl::Status MarkRefusal(absl::Status status, absl::string_view kind) {
  status.SetPayload(kRefusalKindUrl, absl::Cord(kind));
  return status;
}

std::optional<std::string> RefusalKind(const absl::Status& status) {
  const auto kind = status.GetPayload(kRefusalKindUrl);
  if (!kind) return std::nullopt;
  return std::string(*kind);
}

}  // namespace aperture
