// Replays a frame's measured task times through the renderer's dispatch: `workers`
// threads each take the next task in plan order from a shared counter as soon as they are free.
// It tells what a plan would do on more cores than the machine at hand has.
#pragma once

#include <vector>

namespace aperture {

// The time the last worker finishes (the frame's raster time without the planning), in the
// units of `task_times`. 0 for no tasks; `workers` below 1 counts as 1.
double ReplayDispatch(const std::vector<double>& task_times, int workers);

}  // namespace aperture
