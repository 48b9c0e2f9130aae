// A frame's working memory against its budget. What a frame holds that grows with the scene and
// with what its pixels see (the projected polygons, the planned tasks, each worker's leaves and
// cell buffers, the image) is added up as it grows; a frame that would pass its budget stops and
// answers RESOURCE_EXHAUSTED naming the budget, instead of growing the process until the machine
// kills it. Between two looks at the budget a worker's growth is bounded (a cell's exact coverage
// holds memory in proportion to the polygons that reach it; a leaf looks after each row of its
// cells, and before it bins its polygons), so a frame never holds much more than its budget.
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>

#include "absl/status/status.h"

namespace aperture {

class FrameMemory {
 public:
  // `budget_bytes` 0: no budget (the total is still kept).
  explicit FrameMemory(size_t budget_bytes) : budget_(budget_bytes) {}

  // Records that a holder (a worker, the frame's geometry) now holds `bytes`, where it held
  // `held` before (updated). False once the frame's total has passed the budget, and ever after.
  bool Hold(size_t& held, size_t bytes);
  // What the budget leaves for more (SIZE_MAX without a budget): asked before a part is made
  // whose size is known ahead (the projected polygons, a leaf's bins).
  size_t Room() const;
  bool Exceeded() const { return exceeded_.load(std::memory_order_relaxed); }
  size_t Peak() const { return peak_.load(std::memory_order_relaxed); }
  // RESOURCE_EXHAUSTED naming what would not fit and the budget.
  absl::Status Error() const;
  // Notes that `what` (`bytes` more) would not fit, so that Error() names it.
  void Refuse(const char* what, size_t bytes);

 private:
  const size_t budget_;
  std::atomic<size_t> total_{0}, peak_{0};
  std::atomic<bool> exceeded_{false};
  std::atomic<const char*> refused_what_{nullptr};
  std::atomic<size_t> refused_bytes_{0};
};

// A default frame budget for this machine: a quarter of its physical memory.
size_t DefaultFrameBudgetBytes();

}  // namespace aperture
