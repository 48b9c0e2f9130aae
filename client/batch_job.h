// A batch job file (JSON): a scene, frame options and the cameras, listed or as a straight path.
//   {"scene": "demo" | "FILE.json", "size": "640x480", "filter": "trilinear",
//    "cameras": ["X,Y,Z,YAW,PITCH,ROLL", ...]}
//   or "path": {"from": "X,Y,Z,YAW,PITCH,ROLL", "to": "...", "frames": N} instead of "cameras".
// Other frame flags (--aa, --compression, ...) come from the command line.
#pragma once

#include <cstddef>
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

// One shard of a job's frames (`aperture batch --shard I/N`): frame f belongs to shard f mod N,
// so shards interleave along a camera path (equal counts within one frame, and a path's costly
// stretch is spread over all of them). Frames keep their job-wide numbers (frame_%06d.exr), so the
// shards of one job write into one directory without clashing.
struct Shard {
  size_t index = 0;  // I, 0 <= I < N
  size_t count = 1;  // N >= 1; {0, 1}: the whole job
  bool Owns(size_t frame) const { return frame % count == index; }
};

// "I/N" with 0 <= I < N; empty: the whole job.
absl::StatusOr<Shard> ParseShard(const std::string& text);

}  // namespace aperture
