// The CPU time this process has used, for a cost per frame that a shared machine's wall clock
// cannot give.
#pragma once

namespace aperture {

// User + system CPU seconds of every thread of this process so far (getrusage).
double ProcessCpuSeconds();

}  // namespace aperture
