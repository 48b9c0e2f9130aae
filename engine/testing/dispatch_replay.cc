#include "testing/dispatch_replay.h"

#include <algorithm>
#include <functional>
#include <queue>

namespace aperture {

double ReplayDispatch(const std::vector<double>& task_times, int workers) {
  // Free times of the workers, earliest on top: the next task goes to the first one free.
  std::priority_queue<double, std::vector<double>, std::greater<>> free_at;
  for (int i = 0; i < std::max(1, workers); ++i) free_at.push(0);
  double makespan = 0;
  for (double t : task_times) {
    const double done = free_at.top() + t;
    free_at.pop();
    free_at.push(done);
    makespan = std::max(makespan, done);
  }
  return makespan;
}

}  // namespace aperture
