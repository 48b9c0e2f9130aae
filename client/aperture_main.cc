// aperture: the command-line client of the render service (speaks only the proto).
#include <cstdio>
#include <string>
#include <vector>

#include "absl/flags/parse.h"
#include "absl/flags/usage.h"
#include "cli_usage.h"
#include "client_flags.h"
#include "commands.h"
#include "flag_names.h"
#include "large_buffers.h"

int main(int argc, char** argv) {
  aperture::KeepLargeBuffersWarm();  // frames' buffers reused warm, not page-faulted afresh
  aperture::HandleHelpAndVersion(
      argc, argv, "aperture",
      "client of aperture-server.\n"
      "  aperture render --server ADDR --scene NAME|FILE.json|MODEL.glb --camera "
      "X,Y,Z,YAW,PITCH,ROLL "
      "--size WxH -o frame.exr\n"
      "  aperture render --split K --servers A,B,... [same options]: one frame over servers\n"
      "  aperture load --server ADDR --concurrency N (--requests M | --duration S) --size WxH "
      "[--json]\n"
      "  aperture sim --server ADDR --rate HZ --frames N [--path FILE]\n"
      "               [--channels N|NxW|NxWxV|FILE] [--servers A,B,...]\n"
      "  aperture batch JOB.json --servers HOST:PORT,... -o DIR [--concurrency N] "
      "[--shard I/N] [--nocontact_sheet]\n"
      "  aperture batch JOB.json --check -o DIR [--shard I/N]: every frame present and valid?\n"
      "  aperture health --server ADDR\n"
      "  aperture info --server ADDR\n"
      "  aperture COMMAND --help: the flags of one command",
      /*has_commands=*/true);
  aperture::DashedFlagNames dashed(argc, argv);
  std::vector<char*> args = absl::ParseCommandLine(dashed.argc(), dashed.argv());
  const std::string command = args.size() > 1 ? args[1] : "";
  if (absl::Status flags = aperture::CheckClientFlags(); !flags.ok()) {
    std::fprintf(stderr, "aperture: error: %s\n", std::string(flags.message()).c_str());
    return 2;
  }
  if (command == "batch") {
    if (args.size() != 3) {
      std::fprintf(stderr, "aperture batch: give one JOB.json\n");
      return 2;
    }
    return aperture::RunBatch(args[2]);
  }
  if (args.size() > 2) {
    std::fprintf(stderr, "aperture: unexpected argument '%s'\n", args[2]);
    return 2;
  }
  if (command == "render") return aperture::RunRender();
  if (command == "health") return aperture::RunHealth();
  if (command == "info") return aperture::RunInfo();
  if (command == "load") return aperture::RunLoad();
  if (command == "sim") return aperture::RunSim();
  std::fprintf(stderr,
               "aperture: unknown command '%s' (render, batch, load, sim, health, info); "
               "see --help\n",
               command.c_str());
  return 2;
}
