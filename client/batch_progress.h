// What `aperture batch` shows while it runs: frames done and failed, frames per second, the time
// left, and each server's tally (the peer that answered each request). On a terminal one line is
// redrawn in place at most 10 times a second; otherwise (a log file, a job array's output) a plain
// line is printed after every 10 % of the frames, or after 5 seconds without one, and at the end.
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdio>
#include <map>
#include <mutex>
#include <string>

namespace aperture {

class BatchProgress {
 public:
  BatchProgress(size_t frames, std::FILE* out, bool terminal);

  enum class Outcome { kRendered, kSkipped, kFailed };
  void Finish(Outcome outcome);
  // A request answered by `peer` (gRPC's peer string) succeeded or failed; a failed frame may
  // still be retried on another server.
  void Attempt(const std::string& peer, bool ok);
  // A line of its own (why a frame failed), above the redrawn progress line on a terminal.
  void Note(const std::string& line);
  // The last line, always printed (ends the redrawn line on a terminal).
  void Close();

 private:
  struct Tally {
    size_t ok = 0, failed = 0;
  };
  std::string Line() const;  // with mutex_ held
  void Print(bool force);    // with mutex_ held

  const size_t frames_;
  std::FILE* const out_;
  const bool terminal_;
  const std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
  std::chrono::steady_clock::time_point last_print_{};
  std::mutex mutex_;
  size_t rendered_ = 0, skipped_ = 0, failed_ = 0, last_printed_done_ = 0;
  std::map<std::string, Tally> servers_;
};

}  // namespace aperture
