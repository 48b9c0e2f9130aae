// aperture-tex: texture tools (prefiltered tables, packed vector textures, the shared store).
#include <spdlog/cfg/env.h>
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <string>

#include "tools/tex_commands.h"

namespace aperture {
namespace {

std::vector<TexCommand> AllCommands() {
  std::vector<TexCommand> all = PrefilteredTableCommands();
  for (const TexCommand& c : PackedTextureCommands()) all.push_back(c);
  for (const TexCommand& c : StoreCommands()) all.push_back(c);
  return all;
}

int Usage(FILE* out) {
  std::fprintf(out, "usage: aperture-tex COMMAND [ARGS...]\n\ncommands:\n");
  std::vector<std::string> listed;  // `info` is registered by both families: list it once
  for (const TexCommand& c : AllCommands()) {
    if (std::find(listed.begin(), listed.end(), c.name) != listed.end()) continue;
    listed.push_back(c.name);
    std::fprintf(out, "  %-14s %s\n", c.name, c.summary);
  }
  std::fprintf(out, "\n'aperture-tex COMMAND --help' describes one command.\n");
  return out == stdout ? 0 : 2;
}

}  // namespace
}  // namespace aperture

int main(int argc, char** argv) {
  using namespace aperture;
  // Engine log lines (tables built, stores opened) on stderr, stdout kept for the tool's own
  // report; the level from SPDLOG_LEVEL (e.g. SPDLOG_LEVEL=warn).
  spdlog::set_default_logger(spdlog::stderr_color_mt("aperture-tex"));
  spdlog::cfg::load_env_levels();
  if (argc < 2) return Usage(stderr);
  const std::string command = argv[1];
  if (command == "help" || command == "--help" || command == "-h") return Usage(stdout);
  if (command == "--version") {
    std::printf("aperture-tex %s\n", APERTURE_VERSION);
    return 0;
  }
  // `info` is shared: a file's magic tells which family describes it; each family's `info`
  // returns 3 for "not mine" so the next one can try.
  int last = -1;
  for (const TexCommand& c : AllCommands()) {
    if (command != c.name) continue;
    last = c.run(argc - 1, argv + 1);
    if (last != 3) return last;
  }
  if (last == 3) {
    std::fprintf(stderr, "aperture-tex %s: file format not recognised\n", command.c_str());
    return 2;
  }
  std::fprintf(stderr, "aperture-tex: unknown command '%s'\n\n", command.c_str());
  return Usage(stderr);
}
