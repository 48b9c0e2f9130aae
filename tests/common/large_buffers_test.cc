// KeepLargeBuffersWarm: a frame-sized block freed and asked for again comes back without page
// faults. By default glibc serves a block of more than 32 MiB with mmap, whatever came before, and
// unmaps it on free, so every frame of that size would fault each of its pages in again.
#include "large_buffers.h"

#include <gtest/gtest.h>
#include <sys/resource.h>

#include <cstddef>
#include <cstdlib>

namespace aperture {
namespace {

long ThreadMinorFaults() {
  rusage usage{};
  getrusage(RUSAGE_THREAD, &usage);
  return usage.ru_minflt;
}

// Writes one byte of every page (volatile: the writes are the point, not their values).
void TouchPages(void* block, size_t bytes) {
  auto* bytes_of = static_cast<volatile char*>(block);
  for (size_t i = 0; i < bytes; i += 4096) bytes_of[i] = 1;
}

TEST(LargeBuffers, AFrameSizedBlockFreedComesBackWithoutPageFaults) {
  KeepLargeBuffersWarm();
  constexpr size_t kBytes = size_t{48} << 20;  // a 2560x1440 float frame is 59 MB
  constexpr long kPages = static_cast<long>(kBytes / 4096);
  void* first = std::malloc(kBytes);
  ASSERT_NE(first, nullptr);
  TouchPages(first, kBytes);
  std::free(first);
  const long before = ThreadMinorFaults();
  void* second = std::malloc(kBytes);
  ASSERT_NE(second, nullptr);
  TouchPages(second, kBytes);
  const long faults = ThreadMinorFaults() - before;
  std::free(second);
  EXPECT_LT(faults, kPages / 10) << "of " << kPages << " pages";
}

}  // namespace
}  // namespace aperture
