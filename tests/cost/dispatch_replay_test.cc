#include "testing/dispatch_replay.h"

#include <gtest/gtest.h>

#include <numeric>

namespace aperture {
namespace {

TEST(DispatchReplay, OneWorkerRunsEverythingInTurn) {
  EXPECT_DOUBLE_EQ(ReplayDispatch({3, 1, 4, 1, 5}, 1), 14);
  EXPECT_DOUBLE_EQ(ReplayDispatch({3, 1, 4, 1, 5}, 0), 14);
  EXPECT_DOUBLE_EQ(ReplayDispatch({}, 4), 0);
}

TEST(DispatchReplay, TasksGoToTheFirstFreeWorkerInPlanOrder) {
  // Two workers: 2 | 2 at t = 0, then 3 (t = 2..5) and 3 (t = 2..5), then 6 (t = 5..11).
  EXPECT_DOUBLE_EQ(ReplayDispatch({2, 2, 3, 3, 6}, 2), 11);
  // The same tasks most expensive first (longest processing time): 6 | 3, 3 | 2 -> 6 | 3 3, then
  // the 2s go to the worker free at 6 and the other free at 6: finish at 8.
  EXPECT_DOUBLE_EQ(ReplayDispatch({6, 3, 3, 2, 2}, 2), 8);
}

TEST(DispatchReplay, ManyWorkersEndWithTheLongestTaskAndNeverBeatTheAverage) {
  const std::vector<double> tasks = {1, 9, 2, 2, 2, 1, 1};
  EXPECT_DOUBLE_EQ(ReplayDispatch(tasks, 100), 9);
  for (int w = 1; w <= 8; ++w)
    EXPECT_GE(ReplayDispatch(tasks, w), std::accumulate(tasks.begin(), tasks.end(), 0.0) / w);
}

}  // namespace
}  // namespace aperture
