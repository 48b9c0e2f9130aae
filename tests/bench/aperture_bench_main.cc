// aperture-bench: the texture benchmarks (filters, flicker, packed textures), apart from the
// installed aperture-tex so that the product ships no lab code (engine/testing/).
#include <spdlog/cfg/env.h>
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include <cstdio>
#include <string>
#include <vector>

#include "bench/bench_commands.h"

namespace aperture::bench {
namespace {

std::vector<BenchCommand> AllCommands() {
  std::vector<BenchCommand> all = FilterCommands();
  for (const BenchCommand& c : FlickerCommands()) all.push_back(c);
  for (const BenchCommand& c : PackedCommands()) all.push_back(c);
  return all;
}

int Usage(FILE* out) {
  std::fprintf(out, "usage: aperture-bench COMMAND [ARGS...]\n\ncommands:\n");
  for (const BenchCommand& c : AllCommands()) std::fprintf(out, "  %-14s %s\n", c.name, c.summary);
  std::fprintf(out, "\n'aperture-bench COMMAND --help' describes one command.\n");
  return out == stdout ? 0 : 2;
}

}  // namespace
}  // namespace aperture::bench

int main(int argc, char** argv) {
  using namespace aperture::bench;
  // Engine log lines (tables built) on stderr, stdout kept for the benchmark's tables; the level
  // from SPDLOG_LEVEL (e.g. SPDLOG_LEVEL=warn).
  spdlog::set_default_logger(spdlog::stderr_color_mt("aperture-bench"));
  spdlog::cfg::load_env_levels();
  if (argc < 2) return Usage(stderr);
  const std::string command = argv[1];
  if (command == "help" || command == "--help" || command == "-h") return Usage(stdout);
  if (command == "--version") {
    std::printf("aperture-bench %s\n", APERTURE_VERSION);
    return 0;
  }
  for (const BenchCommand& c : AllCommands())
    if (command == c.name) return c.run(argc - 1, argv + 1);
  std::fprintf(stderr, "aperture-bench: unknown command '%s'\n\n", command.c_str());
  return Usage(stderr);
}
