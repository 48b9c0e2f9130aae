// Subcommands of `aperture-bench`, the benchmarks of the texture filters and packed textures: a
// lab tool built beside the tests, never installed (the installed aperture-tex holds the product's
// texture commands).
#pragma once

#include <vector>

namespace aperture::bench {

struct BenchCommand {
  const char* name;
  const char* summary;                // one line for `aperture-bench help`
  int (*run)(int argc, char** argv);  // argv[0] is the subcommand name; returns the exit code
};

// The grazing-plane benchmark of every filter against a supersampled reference: filter.
std::vector<BenchCommand> FilterCommands();
// The filters' temporal stability on a slow turning fly-over: flicker.
std::vector<BenchCommand> FlickerCommands();
// Packed vector textures' sizes and access times (seed 001): packed.
std::vector<BenchCommand> PackedCommands();

}  // namespace aperture::bench
