// What the benchmark commands share (aperture-bench, peer_bench): number lists, the textures the
// filter benchmarks load (the checkerboard or photos) and their cached supersampled references.
#pragma once

#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "base/image.h"
#include "testing/grazing_plane.h"

namespace aperture {

namespace bench {
// Prints "aperture-bench COMMAND: MESSAGE" on stderr; returns 2 (a usage error).
int Fail(const char* command, const std::string& message);
}  // namespace bench

// "5,20,60": finite numbers; `what` names the option in the error.
absl::StatusOr<std::vector<double>> ParseNumbers(const std::string& text, const char* what);

struct BenchTexture {
  std::string name;
  Image image;
};

// "checker" (1024 x 1024, 8 x 8 cells) or image files by path or by name in `data_dir`
// (".png" added), resized to a power of two.
absl::StatusOr<std::vector<BenchTexture>> LoadBenchTextures(const std::string& list,
                                                            const std::string& data_dir);

// The supersampled reference of a grazing-plane view (RenderGroundReference), loaded from
// `cache_dir` when an earlier run wrote it there (its file name holds every parameter), else
// computed and written there; *cached tells which. aperture-bench filter and peer_bench share
// the cache.
absl::StatusOr<Image> CachedReference(const GrazingPlaneView& view, const BenchTexture& texture,
                                      double density, int max_per_side, int min_per_side,
                                      const std::string& cache_dir, bool* cached);

}  // namespace aperture
