#include "refusal_log.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <chrono>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace aperture {
namespace {

using std::chrono::milliseconds;
using ::testing::HasSubstr;
using ::testing::StartsWith;
using Clock = RefusalLog::Clock;

class RefusalLogTest : public ::testing::Test {
 protected:
  RefusalLog::Sink Collect() {
    return [this](const std::string& line) {
      std::lock_guard lock(mutex_);
      lines_.push_back(line);
    };
  }
  std::vector<std::string> Lines() {
    std::lock_guard lock(mutex_);
    return lines_;
  }

  const Clock::time_point t0_ = Clock::now();
  std::mutex mutex_;
  std::vector<std::string> lines_;
};

TEST_F(RefusalLogTest, AFloodIsOneLineASecondWithItsCount) {
  RefusalLog log(Collect());
  // 10,000 refusals over 2.5 s: the first at once, then one line a second.
  for (int i = 0; i < 10000; ++i)
    log.Refused("queue full", "frame", "req=" + std::to_string(i), t0_ + milliseconds(i / 4));
  const std::vector<std::string> lines = Lines();
  ASSERT_EQ(lines.size(), 3u);
  EXPECT_EQ(lines[0], "refused 1 frame: queue full; req=0");
  EXPECT_EQ(lines[1], "refused 4000 frames in the last 1.0 s: queue full; the latest: req=4000");
  EXPECT_EQ(lines[2], "refused 4000 frames in the last 1.0 s: queue full; the latest: req=8000");
  // The tail (1999 refusals) waits for the next line or a flush; nothing is lost.
  log.Flush(t0_ + milliseconds(2600));
  ASSERT_EQ(Lines().size(), 3u) << "not yet an interval since the last line";
  log.Flush(t0_ + milliseconds(3000));
  ASSERT_EQ(Lines().size(), 4u);
  EXPECT_EQ(Lines()[3], "refused 1999 frames in the last 1.0 s: queue full; the latest: req=9999");
}

TEST_F(RefusalLogTest, KindsAndThingsAreCountedApart) {
  RefusalLog log(Collect());
  for (int i = 0; i < 3; ++i) {
    const auto now = t0_ + milliseconds(10 * i);
    log.Refused("queue full", "frame", "a", now);
    log.Refused("over the loaded scenes' budget", "scene load", "b", now);
    log.Refused("queue full", "upload", "c", now);
  }
  std::vector<std::string> lines = Lines();
  ASSERT_EQ(lines.size(), 3u);  // the first of each at once
  EXPECT_EQ(lines[1], "refused 1 scene load: over the loaded scenes' budget; b");
  log.Flush(t0_ + milliseconds(100), /*all=*/true);
  lines = Lines();
  ASSERT_EQ(lines.size(), 6u);
  for (size_t i = 3; i < 6; ++i) EXPECT_THAT(lines[i], StartsWith("refused 2 "));
  EXPECT_THAT(lines[3], HasSubstr("scene loads in the last 0.1 s"));
}

TEST_F(RefusalLogTest, ARefusalAfterAQuietIntervalIsWrittenAtOnce) {
  RefusalLog log(Collect());
  log.Refused("unauthenticated", "call", "x", t0_);
  log.Refused("unauthenticated", "call", "y", t0_ + std::chrono::seconds(60));
  ASSERT_EQ(Lines().size(), 2u);
  EXPECT_EQ(Lines()[1], "refused 1 call: unauthenticated; y");
}

TEST_F(RefusalLogTest, TheDestructorAndTheFlushingThreadWriteWhatIsCounted) {
  {
    RefusalLog log(Collect());
    log.Refused("queue full", "frame", "a");
    log.Refused("queue full", "frame", "b");
  }
  ASSERT_EQ(Lines().size(), 2u);
  EXPECT_THAT(Lines()[1], StartsWith("refused 1 frame: queue full; b"));

  RefusalLog log(Collect(), milliseconds(20));
  log.StartFlushing();
  log.Refused("queue full", "frame", "c");
  log.Refused("queue full", "frame", "d");
  log.Refused("queue full", "frame", "e");
  for (int i = 0; i < 500 && Lines().size() < 4; ++i) std::this_thread::sleep_for(milliseconds(2));
  ASSERT_EQ(Lines().size(), 4u);
  EXPECT_THAT(Lines()[3], StartsWith("refused 2 frames in the last "));
  EXPECT_THAT(Lines()[3], HasSubstr("the latest: e"));
}

TEST(RefusalKind, TravelsWithTheStatus) {
  const absl::Status plain = absl::ResourceExhaustedError("busy");
  EXPECT_FALSE(RefusalKind(plain).has_value());
  const absl::Status marked = MarkRefusal(plain, "queue full");
  EXPECT_EQ(RefusalKind(marked), "queue full");
  EXPECT_EQ(marked.code(), absl::StatusCode::kResourceExhausted);
  EXPECT_EQ(marked.message(), "busy");
}

}  // namespace
}  // namespace aperture
