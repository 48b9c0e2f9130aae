#include "batch_progress.h"

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"

namespace aperture {

BatchProgress::BatchProgress(size_t frames, std::FILE* out, bool terminal)
    : frames_(frames), out_(out), terminal_(terminal) {}

void BatchProgress::Attempt(const std::string& peer, bool ok) {
  std::lock_guard lock(mutex_);
  if (peer.empty()) return;
  // gRPC names peers "ipv4:host:port" or "ipv6:[host]:port": the address is what a person reads.
  const size_t colon = peer.find(':');
  Tally& t =
      servers_[peer.rfind("ipv", 0) == 0 && colon != std::string::npos ? peer.substr(colon + 1)
                                                                       : peer];
  (ok ? t.ok : t.failed)++;
}

void BatchProgress::Finish(Outcome outcome) {
  std::lock_guard lock(mutex_);
  (outcome == Outcome::kRendered ? rendered_ : outcome == Outcome::kSkipped ? skipped_ : failed_)++;
  Print(/*force=*/false);
}

void BatchProgress::Close() {
  std::lock_guard lock(mutex_);
  Print(/*force=*/true);
  if (terminal_) std::fputc('\n', out_);
  std::fflush(out_);
}

std::string BatchProgress::Line() const {
  const size_t done = rendered_ + skipped_ + failed_;
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const double rate = elapsed > 0 ? rendered_ / elapsed : 0;
  std::string line = absl::StrFormat(
      "%zu/%zu frames (%zu rendered, %zu skipped, %zu failed), "
      "%.2f frames/s",
      done, frames_, rendered_, skipped_, failed_, rate);
  if (done < frames_)
    absl::StrAppend(&line, rate > 0 ? absl::StrFormat(", ETA %.0f s", (frames_ - done) / rate)
                                    : std::string(", ETA -"));
  std::string servers;
  for (const auto& [peer, t] : servers_)
    absl::StrAppend(&servers, servers.empty() ? "" : ", ", peer, " ", t.ok, " ok",
                    t.failed > 0 ? absl::StrCat(" ", t.failed, " failed") : "");
  if (!servers.empty()) absl::StrAppend(&line, "; servers: ", servers);
  return line;
}

void BatchProgress::Note(const std::string& line) {
  std::lock_guard lock(mutex_);
  if (terminal_) {
    std::fprintf(out_, "\r\033[K%s\n", line.c_str());
    Print(true);
  } else {
    std::fprintf(out_, "%s\n", line.c_str());
    std::fflush(out_);
  }
}

void BatchProgress::Print(bool force) {
  const auto now = std::chrono::steady_clock::now();
  const size_t done = rendered_ + skipped_ + failed_;
  const double since = std::chrono::duration<double>(now - last_print_).count();
  if (terminal_) {
    if (!force && since < 0.1) return;
    std::fprintf(out_, "\r\033[K%s", Line().c_str());
  } else {
    const size_t step = frames_ >= 10 ? frames_ / 10 : 1;
    if (!force && done < last_printed_done_ + step && since < 5) return;
    std::fprintf(out_, "progress: %s\n", Line().c_str());
    last_printed_done_ = done;
  }
  std::fflush(out_);
  last_print_ = now;
}

}  // namespace aperture
