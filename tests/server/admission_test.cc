// Admission control: a cap on frames rendering, a first-come queue of bounded
// length, refusal past it, and a waiter that leaves when its stop test says so.
#include "admission.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <optional>
#include <thread>
#include <vector>

#include "refusal_log.h"

namespace aperture {
namespace {

using namespace std::chrono_literals;

bool Never() { return false; }

void WaitFor(const std::function<bool()>& condition) {
  for (int i = 0; i < 2000 && !condition(); ++i) std::this_thread::sleep_for(1ms);
  ASSERT_TRUE(condition());
}

TEST(AdmissionControl, AtMostConcurrentRunAndTheQueueIsBounded) {
  AdmissionControl admission(2, 1);
  auto a = admission.Enter(Never);
  auto b = admission.Enter(Never);
  ASSERT_TRUE(a.ok() && b.ok());
  EXPECT_EQ(admission.running(), 2);

  std::optional<absl::StatusOr<AdmissionControl::Ticket>> waited;
  std::thread waiter([&] { waited.emplace(admission.Enter(Never)); });
  WaitFor([&] { return admission.queued() == 1; });
  // The queue holds one: the next is refused at once, and counted.
  const auto refused = admission.Enter(Never);
  EXPECT_TRUE(absl::IsResourceExhausted(refused.status())) << refused.status();
  EXPECT_EQ(RefusalKind(refused.status()), "queue full");  // logged as a counted refusal
  EXPECT_EQ(admission.rejected(), 1u);

  { auto done = *std::move(a); }  // a turn ends: the waiter takes it
  waiter.join();
  ASSERT_TRUE(waited->ok());
  EXPECT_EQ(admission.running(), 2);
  EXPECT_EQ(admission.queued(), 0);
}

TEST(AdmissionControl, WaitersTakeTurnsInArrivalOrder) {
  AdmissionControl admission(1, 8);
  std::optional<absl::StatusOr<AdmissionControl::Ticket>> running(admission.Enter(Never));
  ASSERT_TRUE(running->ok());
  std::mutex mutex;
  std::vector<int> order;
  std::vector<std::thread> waiters;
  for (int i = 0; i < 4; ++i) {
    waiters.emplace_back([&, i] {
      auto ticket = admission.Enter(Never);
      ASSERT_TRUE(ticket.ok());
      std::lock_guard lock(mutex);
      order.push_back(i);
    });
    WaitFor([&] { return admission.queued() == i + 1; });  // arrivals one after another
  }
  running.reset();  // each waiter's ticket ends with its thread, letting the next in
  for (std::thread& t : waiters) t.join();
  EXPECT_EQ(order, (std::vector<int>{0, 1, 2, 3}));
}

TEST(AdmissionControl, AStoppedWaiterLeavesTheQueueAtOnce) {
  AdmissionControl admission(1, 4);
  auto running = admission.Enter(Never);
  ASSERT_TRUE(running.ok());
  std::atomic<bool> stop{false};
  std::optional<absl::StatusOr<AdmissionControl::Ticket>> waited;
  std::thread waiter([&] { waited.emplace(admission.Enter([&] { return stop.load(); })); });
  WaitFor([&] { return admission.queued() == 1; });
  const auto stopped_at = std::chrono::steady_clock::now();
  stop = true;
  waiter.join();
  EXPECT_LT(std::chrono::steady_clock::now() - stopped_at, 200ms);  // polled every 5 ms
  EXPECT_TRUE(absl::IsCancelled(waited->status())) << waited->status();
  EXPECT_EQ(admission.queued(), 0);
  EXPECT_EQ(admission.running(), 1);
}

}  // namespace
}  // namespace aperture
