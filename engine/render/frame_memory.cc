#include "render/frame_memory.h"

#include <unistd.h>

#include <algorithm>

#include "absl/strings/str_cat.h"

namespace aperture {
namespace {

int64_t MiB(size_t bytes) { return static_cast<int64_t>((bytes + (1 << 20) - 1) >> 20); }

}  // namespace

bool FrameMemory::Hold(size_t& held, size_t bytes) {
  // Unsigned wrap-around makes a release (bytes < held) a subtraction.
  const size_t delta = bytes - held;
  const size_t total = total_.fetch_add(delta, std::memory_order_relaxed) + delta;
  held = bytes;
  size_t peak = peak_.load(std::memory_order_relaxed);
  while (total > peak && !peak_.compare_exchange_weak(peak, total, std::memory_order_relaxed)) {
  }
  if (budget_ > 0 && total > budget_) exceeded_.store(true, std::memory_order_relaxed);
  return !Exceeded();
}

size_t FrameMemory::Room() const {
  if (budget_ == 0) return SIZE_MAX;
  const size_t total = total_.load(std::memory_order_relaxed);
  return total < budget_ ? budget_ - total : 0;
}

void FrameMemory::Refuse(const char* what, size_t bytes) {
  refused_what_.store(what, std::memory_order_relaxed);
  refused_bytes_.store(bytes, std::memory_order_relaxed);
  exceeded_.store(true, std::memory_order_relaxed);
}

absl::Status FrameMemory::Error() const {
  const char* what = refused_what_.load(std::memory_order_relaxed);
  const size_t held = total_.load(std::memory_order_relaxed);
  return absl::ResourceExhaustedError(
      absl::StrCat("the frame's working memory would pass its budget of ", MiB(budget_), " MiB",
                   what ? absl::StrCat(": ", what, " would add ", MiB(refused_bytes_.load()),
                                       " MiB to the ", MiB(held), " MiB it holds")
                        : absl::StrCat(" (it reached ", MiB(std::max(held, peak_.load())), " MiB)"),
                   " (the server's --max-frame-mb, aperture-render's --max_frame_mb)"));
}

size_t DefaultFrameBudgetBytes() {
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGE_SIZE);
  if (pages <= 0 || page <= 0) return size_t{4} << 30;
  return static_cast<size_t>(pages) * static_cast<size_t>(page) / 4;
}

}  // namespace aperture
