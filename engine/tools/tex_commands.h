// Subcommands of `aperture-tex`. Each texture family registers its own in its own file. The
// benchmarks are aperture-bench's (tests/bench/), not installed.
#pragma once

#include <vector>

namespace aperture {

struct TexCommand {
  const char* name;
  const char* summary;                // one line for `aperture-tex help`
  int (*run)(int argc, char** argv);  // argv[0] is the subcommand name; returns the exit code
};

// Prefiltered anisotropic tables (seed 000): prefilter, info.
std::vector<TexCommand> PrefilteredTableCommands();
// Packed vector textures (seed 001): pack, unpack, info.
std::vector<TexCommand> PackedTextureCommands();
// The machine's shared texture store: bake, store.
std::vector<TexCommand> StoreCommands();

}  // namespace aperture
