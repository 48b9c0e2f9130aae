// The commands of `aperture`. Each returns the process exit status (exit_status.h): 0 success, 1
// the server said no (or is not serving), 2 bad usage or input.
#pragma once

#include <string>

namespace aperture {

int RunRender();       // upload textures, load the scene, render one frame, write it
int RunSplitRender();  // --split K: one frame's regions over several servers, assembled
int RunHealth();       // grpc.health.v1 Check: 0 when SERVING
int RunInfo();         // GetServerInfo
int RunLoad();         // load test: throughput, latency percentiles, errors by code
int RunSim();          // simulator host: cameras at a fixed rate over RenderStream
int RunBatch(const std::string& job_path);  // a job's frames over several servers, resumable

}  // namespace aperture
