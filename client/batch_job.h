// A batch job file (JSON): a scene, frame options and the cameras, listed or as a straight path.
//   {"scene": "demo" | "FILE.json", "size": "640x480", "filter": "trilinear",
//    "cameras": ["X,Y,Z,YAW,PITCH,ROLL", ...]}
//   or "path": {"from": "X,Y,Z,YAW,PITCH,ROLL", "to": "...", "frames": N} instead of "cameras".
// Other frame flags (--aa, --compression, ...) come from the command line.
#pragma once

#include <string>
#include <vector>

#include "absl/status/statusor.h"

namespace aperture {

struct BatchJob {
  std::string scene = "demo";
  std::string size;                  // empty: --size
  std::string filter;                // empty: --filter
  std::vector<std::string> cameras;  // X,Y,Z,YAW,PITCH,ROLL per frame
};

absl::StatusOr<BatchJob> ReadBatchJob(const std::string& path);

}  // namespace aperture
