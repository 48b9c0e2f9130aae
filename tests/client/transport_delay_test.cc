// The transport delay `aperture sim` reports (client/transport_delay.h): percentiles of host
// received - host sent by nearest rank, the medians of each part, and frames whose four clocks
// are out of order, against frames built with known delays.
#include "transport_delay.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

namespace aperture {
namespace {

constexpr uint64_t kMs = 1'000'000;                        // nanoseconds
constexpr uint64_t kStart = 1'800'000'000'000'000'000ull;  // a Unix time in 2027

// Frame k = 1..100: the request takes 1 ms to arrive, the server holds it 5 ms, the answer takes
// k + 4 ms to come back, so the delay is k + 10 ms; its stages are k/10, k/5, k/20, k/4 ms.
std::vector<FrameClocks> KnownFrames(int64_t server_clock_offset_ns) {
  std::vector<FrameClocks> frames;
  for (uint64_t k = 1; k <= 100; ++k) {
    FrameClocks f;
    f.host_sent_ns = kStart + k * 33 * kMs;
    f.server_received_ns = f.host_sent_ns + 1 * kMs + server_clock_offset_ns;
    f.server_sent_ns = f.server_received_ns + 5 * kMs;
    f.host_received_ns = f.host_sent_ns + (k + 10) * kMs;
    f.wait_ms = static_cast<double>(k) / 10;
    f.render_ms = static_cast<double>(k) / 5;
    f.hold_ms = static_cast<double>(k) / 20;
    f.encode_ms = static_cast<double>(k) / 4;
    frames.push_back(f);
  }
  // Not in the order of their delays: the summary must sort.
  std::swap(frames[3], frames[97]);
  return frames;
}

TEST(TransportDelaySummary, PercentilesByNearestRankAndMediansOfEachPart) {
  const TransportDelay t = SummarizeTransport(KnownFrames(0));
  // Delays 11..110 ms: nearest rank 50 of 100 is the 50th smallest, 60 ms; rank 99 is 109 ms.
  EXPECT_EQ(t.delay_ms.count, 100u);
  EXPECT_DOUBLE_EQ(t.delay_ms.p50, 60);
  EXPECT_DOUBLE_EQ(t.delay_ms.p99, 109);
  EXPECT_DOUBLE_EQ(t.delay_ms.max, 110);
  EXPECT_DOUBLE_EQ(t.request_ms, 1);
  EXPECT_DOUBLE_EQ(t.send_ms, 54);  // k + 4 for k = 50
  EXPECT_DOUBLE_EQ(t.wait_ms, 5);
  EXPECT_DOUBLE_EQ(t.render_ms, 10);
  EXPECT_DOUBLE_EQ(t.hold_ms, 2.5);
  EXPECT_DOUBLE_EQ(t.encode_ms, 12.5);
  EXPECT_EQ(t.unordered, 0u);
}

TEST(TransportDelaySummary, DelayTakesTheHostsClockOnlyAndOffsetClocksAreCounted) {
  // The server's clock 2.5 ms behind the host's: the request seems to arrive 1.5 ms before it was
  // sent; the delay, from the host's clock alone, is unchanged.
  const TransportDelay behind = SummarizeTransport(KnownFrames(-2'500'000));
  EXPECT_DOUBLE_EQ(behind.delay_ms.p50, 60);
  EXPECT_DOUBLE_EQ(behind.delay_ms.max, 110);
  EXPECT_DOUBLE_EQ(behind.request_ms, -1.5);
  EXPECT_DOUBLE_EQ(behind.send_ms, 56.5);
  EXPECT_EQ(behind.unordered, 100u);
  // 20 ms ahead: the answer seems to leave after it arrived for the frames with k + 10 < 26.
  const TransportDelay ahead = SummarizeTransport(KnownFrames(20 * kMs));
  EXPECT_EQ(ahead.unordered, 15u);  // k = 1..15: sent at 26 ms, received at k + 10 ms
}

TEST(TransportDelaySummary, NoFramesGiveZeros) {
  const TransportDelay t = SummarizeTransport({});
  EXPECT_EQ(t.delay_ms.count, 0u);
  EXPECT_EQ(t.delay_ms.p99, 0);
  EXPECT_EQ(t.send_ms, 0);
  EXPECT_EQ(t.unordered, 0u);
}

}  // namespace
}  // namespace aperture
