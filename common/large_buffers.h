// Frames are tens of megabytes (a 1920x1080 half frame is 16.6 MB) and every frame allocates its
// encoded bytes and its message buffers afresh. By default glibc serves such blocks with mmap and
// returns them on free, so each frame's first touch of its buffers page-faults thousands of times
// (about 10 ms a frame on the 2-core machine, as much as the encode itself). Raising malloc's
// mmap and trim thresholds keeps freed frame buffers in the heap, warm, for the next frame.
// Called at the start of the server, the client, aperture-render and the peer benchmark (which
// measures the engine as the server runs it); a no-op outside glibc.
#pragma once

namespace aperture {

void KeepLargeBuffersWarm();

}  // namespace aperture
