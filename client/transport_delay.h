// The transport delay of a live channel's frames: from the host's clock when it sent the state a
// frame shows to the frame's last byte received back, and where that time went, from the four
// clocks each RenderStream answer carries (the host's send time echoed, the server's receive and
// send times, the host's receive time) and the server's stage timings.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "latency_stats.h"

namespace aperture {

// Nanoseconds since the Unix epoch by the system clock: what both ends stamp a frame with.
uint64_t UnixNanosecondsNow();

// One rendered frame: its four clocks (ns since the Unix epoch) and the server's stages (ms).
struct FrameClocks {
  uint64_t host_sent_ns = 0, server_received_ns = 0, server_sent_ns = 0, host_received_ns = 0;
  double wait_ms = 0;    // the stream's wait + the render queue
  double render_ms = 0;  // scene update + setup + raster
  double hold_ms = 0, encode_ms = 0;
};

struct TransportDelay {
  LatencySummary delay_ms;  // host received - host sent, per frame
  // Medians (nearest rank) of each part over the frames, milliseconds: host sent -> server
  // received, the server's stages, server sent -> host received.
  double request_ms = 0, wait_ms = 0, render_ms = 0, hold_ms = 0, encode_ms = 0, send_ms = 0;
  // Frames whose clocks are not in order (host sent <= server received <= server sent <= host
  // received): on one machine none; across two, the clocks' offset shows here.
  size_t unordered = 0;
};

TransportDelay SummarizeTransport(const std::vector<FrameClocks>& frames);

}  // namespace aperture
