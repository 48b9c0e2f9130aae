#include "large_buffers.h"

#include <cstdlib>  // defines __GLIBC__ (through <features.h>) where the C library is glibc's

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace aperture {

void KeepLargeBuffersWarm() {
#if defined(__GLIBC__)
  // Blocks up to 64 MiB (a 3840x2160 float frame's 130 MB still goes to mmap) come from the heap,
  // and up to 128 MiB of freed heap stays mapped per arena. glibc's tunables
  // (GLIBC_TUNABLES=glibc.malloc.mmap_threshold=...) set the same from outside.
  mallopt(M_MMAP_THRESHOLD, 64 << 20);
  mallopt(M_TRIM_THRESHOLD, 128 << 20);
#endif
}

}  // namespace aperture
