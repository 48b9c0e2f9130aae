// What the aperture-tex subcommands share: their `--name value` arguments, number lists, and the
// textures the filter benchmarks load (the checkerboard or photos).
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "absl/status/statusor.h"
#include "base/image.h"
#include "testing/grazing_plane.h"

namespace aperture {

// Prints "aperture-tex COMMAND: MESSAGE" on stderr; returns 2 (a usage error).
int Fail(const char* command, const std::string& message);

// `--name value` options after positional arguments.
struct Args {
  std::vector<std::string> positional;
  std::vector<std::pair<std::string, std::string>> options;
  bool help = false;

  // The last value given for `name` (a later option overrides an earlier one, as in most
  // command lines), else `fallback`.
  std::string Get(const std::string& name, const std::string& fallback) const {
    for (auto it = options.rbegin(); it != options.rend(); ++it)
      if (it->first == name) return it->second;
    return fallback;
  }
};

// An error names an unknown option or one without a value.
absl::StatusOr<Args> ParseArgs(int argc, char** argv, const std::vector<std::string>& known);

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
// computed and written there; *cached tells which. bench-filter and peer_bench share the cache.
absl::StatusOr<Image> CachedReference(const GrazingPlaneView& view, const BenchTexture& texture,
                                      double density, int max_per_side, int min_per_side,
                                      const std::string& cache_dir, bool* cached);

}  // namespace aperture
