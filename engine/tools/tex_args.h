// What the aperture-tex subcommands (and the benchmarks' aperture-bench) share: their
// `--name value` arguments and the usage error.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "absl/status/statusor.h"

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

}  // namespace aperture
