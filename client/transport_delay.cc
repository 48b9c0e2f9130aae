#include "transport_delay.h"

#include <chrono>

namespace aperture {
namespace {

// b - a in milliseconds; negative when the clocks disagree.
double Milliseconds(uint64_t a, uint64_t b) {
  return static_cast<double>(static_cast<int64_t>(b - a)) / 1e6;
}

}  // namespace

uint64_t UnixNanosecondsNow() {
  return static_cast<uint64_t>(std::chrono::duration_cast<std::chrono::nanoseconds>(
                                   std::chrono::system_clock::now().time_since_epoch())
                                   .count());
}

TransportDelay SummarizeTransport(const std::vector<FrameClocks>& frames) {
  std::vector<double> delay, request, wait, render, hold, encode, send;
  TransportDelay t;
  for (const FrameClocks& f : frames) {
    delay.push_back(Milliseconds(f.host_sent_ns, f.host_received_ns));
    request.push_back(Milliseconds(f.host_sent_ns, f.server_received_ns));
    send.push_back(Milliseconds(f.server_sent_ns, f.host_received_ns));
    wait.push_back(f.wait_ms);
    render.push_back(f.render_ms);
    hold.push_back(f.hold_ms);
    encode.push_back(f.encode_ms);
    if (!(f.host_sent_ns <= f.server_received_ns && f.server_received_ns <= f.server_sent_ns &&
          f.server_sent_ns <= f.host_received_ns))
      ++t.unordered;
  }
  t.delay_ms = Summarize(delay);
  t.request_ms = Summarize(request).p50;
  t.wait_ms = Summarize(wait).p50;
  t.render_ms = Summarize(render).p50;
  t.hold_ms = Summarize(hold).p50;
  t.encode_ms = Summarize(encode).p50;
  t.send_ms = Summarize(send).p50;
  return t;
}

}  // namespace aperture
