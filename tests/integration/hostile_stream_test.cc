// What a hostile live stream may make the server do: a client that never reads its answers is
// held back by flow control and leaves the server's memory where it was once it goes; updates
// naming 100,000 objects (or one object 100,000 times) apply within seconds and within their
// deadline; an open stream holds its scene while other clients' loads overflow the scene budget.
// Real servers on loopback, real gRPC calls; the server's RSS read from /proc.
#include <gmock/gmock.h>
#include <grpcpp/grpcpp.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <fstream>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "integration/service_fixture.h"
#include "support/hostile_inputs.h"

namespace aperture::testing {
namespace {

using ::testing::HasSubstr;
using Clock = std::chrono::steady_clock;
using FrameStream = grpc::ClientReaderWriter<v1::RenderFrameRequest, v1::RenderFrameResponse>;

double SecondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

class HostileStreamTest : public ServiceTest {
 protected:
  std::unique_ptr<FrameStream> OpenStream(grpc::ClientContext* context, double seconds) {
    context->set_deadline(std::chrono::system_clock::now() +
                          std::chrono::milliseconds(static_cast<int64_t>(seconds * 1000)));
    return stub_->RenderStream(context);
  }
  // One request on `stream`, and its answer.
  static v1::RenderFrameResponse Exchange(FrameStream& stream,
                                          const v1::RenderFrameRequest& request) {
    v1::RenderFrameResponse response;
    EXPECT_TRUE(stream.Write(request));
    EXPECT_TRUE(stream.Read(&response));
    return response;
  }
};

// Two streams send small valid requests as fast as they can and never read. The server stops
// reading them once their unwritten answers reach the bound, so their writes block (HTTP/2 flow
// control: they stand still) and the server's RSS stays within 200 MB of where it was; once they
// are cancelled it returns to within 30 MB.
TEST_F(HostileStreamTest, StreamsThatNeverReadAreHeldBackAndLeaveNoMemory) {
  StartServer({"--threads=2"});
  const v1::LoadSceneResponse demo = LoadBuiltinScene(*stub_, "demo");
  v1::RenderFrameRequest request = FrameRequest(demo.scene_id(), 64, 48);
  ASSERT_TRUE(Render(request, 30).ok());  // what the scene's first frame builds is not counted
  const double start_mb = server_->ResidentMb();
  ASSERT_GT(start_mb, 0);

  constexpr int kStreams = 2;
  // Held back within seconds as a rule: once the client's HTTP/2 receive window (grown by gRPC's
  // bandwidth probe) is full of unread answers. The bound allows for a loaded machine.
  constexpr double kSendSeconds = 40, kBoundMb = 200;
  struct Unread {
    grpc::ClientContext context;
    std::unique_ptr<FrameStream> stream;
    std::atomic<uint64_t> written{0};
  };
  std::vector<std::unique_ptr<Unread>> streams;
  std::vector<std::thread> writers;
  for (int s = 0; s < kStreams; ++s) {
    auto unread = std::make_unique<Unread>();
    unread->stream = stub_->RenderStream(&unread->context);
    Unread* u = unread.get();
    writers.emplace_back([u, request]() mutable {
      for (uint64_t i = 0;; ++i) {
        request.set_frame_index(i);
        if (!u->stream->Write(request)) return;  // cancelled
        u->written = i + 1;
      }
    });
    streams.push_back(std::move(unread));
  }
  // Sampled while they send, until the writes have stood still for a second (held back: the
  // server reads no more of them); a server that buffers everything is stopped at the bound.
  double peak_mb = start_mb;
  const auto sending = Clock::now();
  auto written = [&] {
    uint64_t sum = 0;
    for (auto& u : streams) sum += u->written.load();
    return sum;
  };
  uint64_t last = written();
  auto still_since = Clock::now();
  bool held_back = false;
  while (SecondsSince(sending) < kSendSeconds && peak_mb < start_mb + kBoundMb) {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    peak_mb = std::max(peak_mb, server_->ResidentMb());
    if (const uint64_t now = written(); now != last) {
      last = now;
      still_since = Clock::now();
    } else if (SecondsSince(still_since) > 1.0) {
      held_back = true;
      break;
    }
  }
  for (auto& u : streams) u->context.TryCancel();
  for (std::thread& t : writers) t.join();
  EXPECT_TRUE(held_back) << "the streams' writes never stood still; " << written() << " written";
  for (auto& u : streams) {
    EXPECT_FALSE(u->stream->Finish().ok());
    EXPECT_GT(u->written.load(), 64u);  // past the server's bound of unwritten answers
  }
  EXPECT_LT(peak_mb, start_mb + kBoundMb) << "from " << start_mb << " MiB";

  // Gone: the server's memory comes back (the handler ends a moment after the cancel).
  double end_mb = server_->ResidentMb();
  for (int i = 0; i < 50 && end_mb > start_mb + 30; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    end_mb = server_->ResidentMb();
  }
  EXPECT_LT(end_mb, start_mb + 30) << "from " << start_mb << " MiB, peak " << peak_mb << " MiB";
  // And it still serves streams.
  grpc::ClientContext context;
  auto stream = OpenStream(&context, 30);
  EXPECT_EQ(Exchange(*stream, request).status_code(), 0);
  stream->WritesDone();
  EXPECT_TRUE(stream->Finish().ok());
}

// Flow control keeps the protocol: a client that writes a thousand requests before reading any
// gets every one answered once, in order, the newest rendered.
TEST_F(HostileStreamTest, AStreamReadLateStillAnswersEveryRequestInOrder) {
  StartServer({"--threads=2"});
  const v1::LoadSceneResponse demo = LoadBuiltinScene(*stub_, "demo");
  grpc::ClientContext context;
  auto stream = OpenStream(&context, 60);
  constexpr int kRequests = 1000;
  for (int i = 0; i < kRequests; ++i) {
    v1::RenderFrameRequest request = FrameRequest(demo.scene_id(), 32, 24);
    request.set_frame_index(static_cast<uint64_t>(i));
    ASSERT_TRUE(stream->Write(request));
  }
  stream->WritesDone();
  const std::vector<v1::RenderFrameResponse> answers = ReadAllAnswers(*stream);
  ASSERT_TRUE(stream->Finish().ok());
  ASSERT_EQ(answers.size(), static_cast<size_t>(kRequests));
  for (int i = 0; i < kRequests; ++i) {
    EXPECT_EQ(answers[i].frame_index(), static_cast<uint64_t>(i));
    EXPECT_EQ(answers[i].status_code(), 0) << answers[i].status_message();
  }
  EXPECT_EQ(answers.back().outcome(), v1::FRAME_OUTCOME_RENDERED);
  EXPECT_FALSE(answers.back().exr().empty());
}

// On a scene of 100,000 named objects: an update naming every one (moving all, hiding half) and
// one naming a single object 100,000 times each apply within a few seconds, and a deadline_ms
// shorter than the update's work answers DEADLINE_EXCEEDED saying so, the state unchanged.
TEST_F(HostileStreamTest, UpdatesNamingAHundredThousandObjectsApplyWithinSecondsAndDeadlines) {
  StartServer({"--threads=2", "--max-message-mb=64"});
  constexpr int kObjects = 100000;
  std::string scene_id;
  {
    grpc::ClientContext context;
    context.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(60));
    v1::LoadSceneRequest load;
    *load.mutable_scene() = ManyObjectsScene(kObjects);
    v1::LoadSceneResponse loaded;
    const grpc::Status status = stub_->LoadScene(&context, load, &loaded);
    ASSERT_TRUE(status.ok()) << status.error_message();
    ASSERT_EQ(loaded.objects_size(), kObjects);
    scene_id = loaded.scene_id();
  }
  v1::RenderFrameRequest frame = FrameRequest(scene_id, 16, 16);
  frame.mutable_camera()->mutable_position()->set_y(30);
  frame.mutable_camera()->set_pitch_deg(-30);
  grpc::ClientContext context;
  auto stream = OpenStream(&context, 30);
  const v1::RenderFrameResponse before = Exchange(*stream, frame);
  ASSERT_EQ(before.status_code(), 0) << before.status_message();

  // Too short a deadline for the work: refused, and nothing of it applies.
  v1::RenderFrameRequest late = frame;
  late.set_deadline_ms(1);
  *late.mutable_update() = UpdateEveryObject(kObjects);
  const v1::RenderFrameResponse refused = Exchange(*stream, late);
  EXPECT_EQ(refused.status_code(), static_cast<int>(grpc::StatusCode::DEADLINE_EXCEEDED));
  EXPECT_THAT(refused.status_message(),
              HasSubstr("the frame's deadline_ms passed while its scene update was"));
  EXPECT_THAT(refused.status_message(), HasSubstr("of 100000"));
  const v1::RenderFrameResponse unchanged = Exchange(*stream, frame);
  ASSERT_EQ(unchanged.status_code(), 0) << unchanged.status_message();
  EXPECT_EQ(Pixels(unchanged), Pixels(before));

  struct Case {
    const char* what;
    v1::SceneUpdate update;
  };
  const Case cases[] = {{"every object once", UpdateEveryObject(kObjects)},
                        {"one object every time", UpdateOneObjectRepeatedly(kObjects, kObjects)}};
  for (const Case& c : cases) {
    SCOPED_TRACE(c.what);
    v1::RenderFrameRequest request = frame;
    *request.mutable_update() = c.update;
    const auto start = Clock::now();
    const v1::RenderFrameResponse answer = Exchange(*stream, request);
    const double seconds = SecondsSince(start);
    EXPECT_EQ(answer.status_code(), 0) << answer.status_message();
    EXPECT_LT(seconds, 5.0);
    EXPECT_LT(answer.timings().update_ms(), 5000);
  }
  stream->WritesDone();
  EXPECT_TRUE(stream->Finish().ok());
}

// A stream that has rendered a frame of its scene holds it: other clients' loads that overflow
// --max-scenes-mb (or --max-scenes) drop another scene, never the stream's, and the stream's next
// frame renders.
TEST_F(HostileStreamTest, AnOpenStreamHoldsItsSceneAgainstEviction) {
  // Checkerboards of 1024 x 1024 texels: 21.3 MiB each as a float mip-map. Two fit in 50 MiB.
  for (const std::string limit : {"--max-scenes-mb=50", "--max-scenes=2"}) {
    SCOPED_TRACE(limit);
    own_server_.reset();
    StartServer({limit});
    std::vector<std::string> ids;
    auto load = [&](uint32_t size) {
      grpc::ClientContext context;
      context.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(30));
      v1::LoadSceneResponse response;
      const grpc::Status status =
          stub_->LoadScene(&context, TexturedGroundScene("", size), &response);
      EXPECT_TRUE(status.ok()) << status.error_message();
      ids.push_back(response.scene_id());
    };
    load(1024);
    grpc::ClientContext context;
    auto stream = OpenStream(&context, 60);
    v1::RenderFrameRequest request = FrameRequest(ids[0], 16, 16);
    ASSERT_EQ(Exchange(*stream, request).status_code(), 0);
    // The stream's scene is now the least recently used: loads past the budget would take it.
    load(1023);
    load(1022);
    EXPECT_EQ(Info().budgets().scenes_evicted(), 1u);
    request.set_frame_index(1);
    const v1::RenderFrameResponse after = Exchange(*stream, request);
    EXPECT_EQ(after.status_code(), 0) << after.status_message();
    EXPECT_FALSE(after.exr().empty());
    // The scene dropped was another one.
    EXPECT_EQ(Render(FrameRequest(ids[1], 16, 16), 10).error_code(), grpc::StatusCode::NOT_FOUND);
    EXPECT_TRUE(Render(FrameRequest(ids[2], 16, 16), 10).ok());
    stream->WritesDone();
    EXPECT_TRUE(stream->Finish().ok());
  }
}

}  // namespace
}  // namespace aperture::testing
