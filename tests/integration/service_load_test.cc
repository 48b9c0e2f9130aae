// Admission control, deadlines and shutdown against a real server: a frame past its deadline
// frees the workers, a full queue answers RESOURCE_EXHAUSTED at once, SIGTERM drains or cancels.
#include <gmock/gmock.h>
#include <grpcpp/grpcpp.h>
#include <gtest/gtest.h>
#include <signal.h>

#include <chrono>
#include <future>
#include <thread>

#include "integration/service_fixture.h"

namespace aperture::testing {
namespace {

using Clock = std::chrono::steady_clock;

double SecondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// Waits until the server reports `running` frames rendering (or 10 s pass).
template <typename InfoFn>
bool WaitForRunning(InfoFn info, uint32_t running) {
  const auto start = Clock::now();
  while (SecondsSince(start) < 10) {
    if (info().frames_in_flight() >= running) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return false;
}

TEST_F(ServiceTest, DeadlineExceededFreesTheWorkers) {
  StartServer({"--threads=1", "--concurrent-frames=1", "--max-queue=4"});
  const std::string scene_id = LoadDemoScene();
  ASSERT_TRUE(Render(FrameRequest(scene_id, 32, 32), 30).ok());  // warm up

  const v1::RenderFrameRequest slow_request = SlowFrame();
  const auto start = Clock::now();
  const grpc::Status slow = Render(slow_request, 0.5);
  EXPECT_EQ(slow.error_code(), grpc::StatusCode::DEADLINE_EXCEEDED);
  EXPECT_LT(SecondsSince(start), 3.0);

  // The slow frame's remaining tiles are dropped: the next frame does not wait behind them.
  const auto next = Clock::now();
  v1::RenderFrameResponse response;
  const grpc::Status quick = Render(FrameRequest(scene_id, 32, 32), 5, &response);
  EXPECT_TRUE(quick.ok()) << quick.error_message();
  EXPECT_LT(SecondsSince(next), 3.0);
}

TEST_F(ServiceTest, FullQueueAnswersResourceExhaustedAtOnce) {
  StartServer({"--threads=1", "--concurrent-frames=1", "--max-queue=1"});
  const std::string scene_id = LoadDemoScene();
  const v1::RenderFrameRequest slow = SlowFrame();
  // One renders, one waits; both give up at their deadline.
  auto running = std::async(std::launch::async, [&] { return Render(slow, 3).error_code(); });
  ASSERT_TRUE(WaitForRunning([&] { return Info(); }, 1));
  auto queued = std::async(std::launch::async, [&] { return Render(slow, 3).error_code(); });
  const auto wait_start = Clock::now();
  while (Info().frames_queued() < 1 && SecondsSince(wait_start) < 5)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));

  const auto start = Clock::now();
  const grpc::Status refused = Render(FrameRequest(scene_id, 32, 32), 10);
  EXPECT_EQ(refused.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED);
  EXPECT_LT(SecondsSince(start), 1.0) << "refused at once, not after a wait";
  EXPECT_THAT(refused.error_message(), ::testing::HasSubstr("--max-queue"));
  EXPECT_EQ(running.get(), grpc::StatusCode::DEADLINE_EXCEEDED);
  EXPECT_EQ(queued.get(), grpc::StatusCode::DEADLINE_EXCEEDED);
  EXPECT_GE(Info().frames_rejected(), 1u);
}

TEST_F(ServiceTest, SigtermLetsShortFramesFinishAndCancelsLongOnes) {
  StartServer({"--threads=2", "--concurrent-frames=2", "--grace-s=2"});
  const v1::RenderFrameRequest slow_request = SlowFrame();
  v1::RenderFrameRequest quick_request = slow_request;  // a 1024th of the slow frame
  quick_request.mutable_region()->set_width(128);
  quick_request.mutable_region()->set_height(128);
  auto slow = std::async(std::launch::async, [&] { return Render(slow_request, 60).error_code(); });
  ASSERT_TRUE(WaitForRunning([&] { return Info(); }, 1));
  auto quick = std::async(std::launch::async, [&] {
    v1::RenderFrameResponse response;
    const grpc::Status status = Render(quick_request, 60, &response);
    return status.ok() && !response.exr().empty() ? std::string("delivered")
                                                  : status.error_message();
  });
  // Both in flight (or the short one already done, which the checks below accept too).
  const auto wait_start = Clock::now();
  while (Info().frames_in_flight() < 2 && SecondsSince(wait_start) < 10 &&
         quick.wait_for(std::chrono::milliseconds(0)) != std::future_status::ready)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));

  const auto start = Clock::now();
  server_->Signal(SIGTERM);
  EXPECT_EQ(quick.get(), "delivered") << "a frame that fits in the grace period is delivered";
  const grpc::StatusCode slow_code = slow.get();
  EXPECT_NE(slow_code, grpc::StatusCode::OK);
  EXPECT_NE(slow_code, grpc::StatusCode::DEADLINE_EXCEEDED);
  const std::optional<int> exit_status = server_->WaitForExit(10);
  ASSERT_TRUE(exit_status.has_value()) << "the server did not exit after SIGTERM\n"
                                       << server_->Log();
  EXPECT_EQ(*exit_status, 0);
  EXPECT_LT(SecondsSince(start), 10.0);
  EXPECT_THAT(server_->Log(), ::testing::HasSubstr("shutting down"));
  if (HasFailure()) ADD_FAILURE() << server_->Log();
}

}  // namespace
}  // namespace aperture::testing
