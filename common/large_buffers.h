// Frames are tens of megabytes (a 1920x1080 half frame is 16.6 MB, its float image 33.2 MB) and
// every frame allocates its image, its encoded bytes and its message buffers afresh. By default
// glibc serves a block above its mmap threshold (which it raises as such blocks are freed, to at
// most 32 MiB) with mmap and unmaps it on free, so each frame's first touch of such a buffer
// page-faults thousands of times (on the 2-core virtual machine a 2560x1440 demo frame's raster
// took 223.9 ms with its image faulted in afresh, 72.9 ms kept: docs/BENCHMARKS.md). Raising
// malloc's mmap and trim thresholds keeps freed frame buffers in the heap, warm, for the next
// frame. Called at the start of the server, the client, aperture-render and the peer benchmark
// (which measures the engine as the server runs it); a no-op outside glibc.
#pragma once

namespace aperture {

void KeepLargeBuffersWarm();

}  // namespace aperture
