// The transport delay's clocks on a real server over loopback, where the host and the server read
// one system clock: every RenderStream answer echoes the host's send time exactly and carries the
// server's receive and send times in order (host sent <= server received <= server sent <= host
// received), the server's stages fit between its two clocks, and `aperture sim --json` reports
// the delay, its parts and the host's CPU per frame.
#include <google/protobuf/util/json_util.h>
#include <grpcpp/grpcpp.h>
#include <gtest/gtest.h>

#include <chrono>
#include <cstdint>
#include <map>
#include <vector>

#include "aperture/v1/client_reports.pb.h"
#include "integration/service_fixture.h"

namespace aperture::testing {
namespace {

uint64_t UnixNs() {
  return static_cast<uint64_t>(std::chrono::duration_cast<std::chrono::nanoseconds>(
                                   std::chrono::system_clock::now().time_since_epoch())
                                   .count());
}

double Ms(uint64_t from, uint64_t to) { return static_cast<double>(to - from) / 1e6; }

// The server's stages are read from its steady clock, its two stamps from the system clock: they
// may disagree by the system clock's slew over a frame, far below this.
constexpr double kClockToleranceMs = 0.5;

class TransportDelayTest : public ServiceTest {
 protected:
  // Checks one answer against the host's clocks of its request: the echo, the order, and for a
  // rendered frame its stages within the server's stay.
  void CheckAnswer(const v1::RenderFrameResponse& a, uint64_t host_sent, uint64_t host_received) {
    SCOPED_TRACE(::testing::Message() << "frame " << a.frame_index());
    EXPECT_EQ(a.host_sent_unix_ns(), host_sent);
    EXPECT_LE(host_sent, a.server_received_unix_ns());
    EXPECT_LE(a.server_received_unix_ns(), a.server_sent_unix_ns());
    EXPECT_LE(a.server_sent_unix_ns(), host_received);
    if (a.outcome() != v1::FRAME_OUTCOME_RENDERED || a.status_code() != 0) return;
    const v1::FrameTimings& t = a.timings();
    EXPECT_GE(t.wait_ms(), 0);
    EXPECT_GE(t.hold_ms(), 0);
    EXPECT_GT(t.raster_ms(), 0);
    EXPECT_GT(t.encode_ms(), 0);
    // One after another between the request's arrival and its answer's send: the stages' sum
    // is at most the total, and the total at most the stay between the server's two stamps.
    const double stages = t.wait_ms() + t.update_ms() + t.queue_ms() + t.setup_ms() +
                          t.raster_ms() + t.hold_ms() + t.encode_ms();
    EXPECT_LE(stages, t.total_ms() + kClockToleranceMs);
    EXPECT_LE(t.total_ms(),
              Ms(a.server_received_unix_ns(), a.server_sent_unix_ns()) + kClockToleranceMs);
  }
};

TEST_F(TransportDelayTest, StreamAnswersCarryTheFourClocksInOrder) {
  StartServer();
  const std::string scene_id = LoadDemoScene();
  grpc::ClientContext context;
  context.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(60));
  auto stream = stub_->RenderStream(&context);
  // Three frames one at a time (each rendered), then eight at once (most superseded, the last
  // rendered, some held while the one before is sent), then one without a send time.
  std::map<uint64_t, uint64_t> sent;
  uint64_t index = 0;
  auto write = [&](bool stamped) {
    v1::RenderFrameRequest request = FrameRequest(scene_id, 160, 90);
    request.set_frame_index(index);
    sent[index] = stamped ? UnixNs() : 0;
    request.set_host_sent_unix_ns(sent[index]);
    ++index;
    return stream->Write(request);
  };
  size_t rendered = 0;
  auto read = [&] {
    v1::RenderFrameResponse answer;
    if (!stream->Read(&answer)) return false;
    const uint64_t received = UnixNs();
    EXPECT_EQ(answer.status_code(), 0) << answer.status_message();
    const auto found = sent.find(answer.frame_index());
    if (found == sent.end()) {
      ADD_FAILURE() << "an answer to frame " << answer.frame_index() << ", never sent";
      return false;
    }
    // Unstamped (0): echoed as 0, the server's own clocks still in order.
    CheckAnswer(answer, found->second, received);
    if (answer.outcome() == v1::FRAME_OUTCOME_RENDERED) ++rendered;
    return true;
  };
  for (int i = 0; i < 3; ++i) {
    ASSERT_TRUE(write(true));
    ASSERT_TRUE(read());
  }
  for (int i = 0; i < 8; ++i) ASSERT_TRUE(write(true));
  for (int i = 0; i < 8; ++i) ASSERT_TRUE(read());
  ASSERT_TRUE(write(false));
  ASSERT_TRUE(read());
  stream->WritesDone();
  ASSERT_TRUE(stream->Finish().ok());
  EXPECT_GE(rendered, 5u);  // the three, the last of the eight, the unstamped one
}

TEST_F(TransportDelayTest, SimReportsTheDelayItsPartsAndTheHostsCpu) {
  StartServer();
  const CommandResult sim =
      RunCommand({APERTURE_CLIENT_BIN, "sim", "--server=" + server_->address(), "--scene=demo",
                  "--size=160x90", "--rate=10", "--frames=12", "--json"},
                 60);
  ASSERT_EQ(sim.exit_code, 0) << sim.err;
  v1::SimReport report;
  ASSERT_TRUE(google::protobuf::util::JsonStringToMessage(sim.out, &report).ok()) << sim.out;
  ASSERT_GT(report.ok(), 0u);
  const v1::TransportDelayMs& t = report.transport_delay_ms();
  EXPECT_GT(t.p50(), 0);
  EXPECT_LE(t.p50(), t.p99());
  EXPECT_LE(t.p99(), t.max());
  // On loopback the host's and the server's clocks are one: every frame's clocks in order.
  EXPECT_EQ(t.unordered(), 0u);
  EXPECT_GE(t.request(), 0);
  EXPECT_GE(t.send(), 0);
  EXPECT_GE(t.wait(), 0);
  EXPECT_GE(t.hold(), 0);
  EXPECT_GT(t.render(), 0);
  EXPECT_GT(t.encode(), 0);
  // The parts are medians of one frame's consecutive stretches: each at most the largest delay.
  for (double part : {t.request(), t.wait(), t.render(), t.hold(), t.encode(), t.send()})
    EXPECT_LE(part, t.max());
  // The delay from the echoed system-clock stamps and the sim's own latency from its steady
  // clock measure the same stretch of every frame.
  EXPECT_NEAR(t.p50(), report.latency_ms().p50(), 2.0);
  EXPECT_NEAR(t.max(), report.latency_ms().max(), 2.0);
  EXPECT_GT(report.host_cpu_ms_per_frame(), 0);
}

}  // namespace
}  // namespace aperture::testing
