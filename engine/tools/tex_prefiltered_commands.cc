// aperture-tex subcommands for prefiltered anisotropic tables (seed 000): prefilter, info.
#include <unistd.h>

#include <cstdio>
#include <string>
#include <vector>

#include "absl/strings/numbers.h"
#include "texture/image_file.h"
#include "texture/prefiltered_table.h"
#include "texture/prefiltered_table_builder.h"
#include "texture/table_column_kernels.h"
#include "tools/tex_args.h"
#include "tools/tex_commands.h"

namespace aperture {
namespace {

// ---- prefilter -------------------------------------------------------------------------------

int RunPrefilter(int argc, char** argv) {
  auto args = ParseArgs(argc, argv, {"-o", "--threads"});
  if (!args.ok()) return Fail("prefilter", std::string(args.status().message()));
  if (args->help || args->positional.size() != 1) {
    std::fprintf(args->help ? stdout : stderr,
                 "usage: aperture-tex prefilter IN -o OUT.apt [--threads N]\n"
                 "Builds seed 000's prefiltered anisotropic table of an image (PNG, JPEG, EXR,\n"
                 "TIFF; resampled to a square power of two when needed).\n");
    return args->help ? 0 : 2;
  }
  const std::string out = args->Get("-o", "");
  if (out.empty()) return Fail("prefilter", "missing -o OUT.apt");
  int threads = 0;
  if (!absl::SimpleAtoi(args->Get("--threads", "0"), &threads) || threads < 0)
    return Fail("prefilter", "--threads must be a whole number >= 0");
  auto image = LoadImageFile(args->positional[0]);
  if (!image.ok()) return Fail("prefilter", std::string(image.status().message()));
  TableBuildOptions options{threads, {}};
  if (isatty(STDERR_FILENO)) {  // a terminal: the build of a 4096^2 table takes half a minute
    options.progress = [last = -1](double done) mutable {
      const int percent = static_cast<int>(done * 100);
      if (percent == last) return;
      last = percent;
      std::fprintf(stderr, "\rprefilter: building the table %3d%%%s", percent,
                   percent == 100 ? "\n" : "");
    };
  }
  auto block = BuildPrefilteredTable(*image, options);
  if (!block.ok()) return Fail("prefilter", std::string(block.status().message()));
  auto table = block->View();
  if (!table.ok()) return Fail("prefilter", std::string(table.status().message()));
  if (auto s = WriteTableFile(out, *block); !s.ok())
    return Fail("prefilter", std::string(s.message()));
  std::printf("%s: %dx%d, %zu copies, %zu bytes, built in %.3f s (%s column kernel)\n", out.c_str(),
              table->size(), table->size(), table->directory().size(), block->bytes.size(),
              table->header().build_milliseconds / 1000.0, BestAddColumnName());
  return 0;
}

// ---- info ------------------------------------------------------------------------------------

int RunInfo(int argc, char** argv) {
  auto args = ParseArgs(argc, argv, {});
  if (!args.ok()) return Fail("info", std::string(args.status().message()));
  if (args->help || args->positional.size() != 1) {
    std::fprintf(args->help ? stdout : stderr, "usage: aperture-tex info FILE\n");
    return args->help ? 0 : 2;
  }
  auto block = ReadTableFile(args->positional[0]);
  if (block.status().code() == absl::StatusCode::kFailedPrecondition) return 3;  // not mine
  if (!block.ok()) return Fail("info", std::string(block.status().message()));
  auto table = block->View();
  if (!table.ok()) return Fail("info", std::string(table.status().message()));
  const TableHeader& h = table->header();
  const int n = table->log2_size();
  uint64_t texels = 0;
  for (const CopyEntry& e : table->directory()) texels += uint64_t{e.width} * e.height;
  std::printf("prefiltered anisotropic table (seed 000), format version %u\n", h.version);
  std::printf("  texture      %dx%d (n = %d), source image %ux%u\n", table->size(), table->size(),
              n, h.source_width, h.source_height);
  std::printf("  copies       %zu in %d cells (L = 2^0..2^%d, H / L = 2^0..2^%d) + base\n",
              table->directory().size() - 1, (n + 1) * n, n, n - 1);
  std::printf("  texels       %llu (n S_n + end tilts + 4^n = %llu + %llu + %llu)\n",
              static_cast<unsigned long long>(texels),
              static_cast<unsigned long long>(n * DiagonalTexels(n)),
              static_cast<unsigned long long>(EndTiltTexels(n)),
              static_cast<unsigned long long>(uint64_t{1} << (2 * n)));
  std::printf("  bytes        %llu (RGBA8; header and directory %llu)\n",
              static_cast<unsigned long long>(h.total_bytes),
              static_cast<unsigned long long>(h.data_offset));
  std::printf("  build time   %.3f s\n", h.build_milliseconds / 1000.0);
  return 0;
}

}  // namespace

std::vector<TexCommand> PrefilteredTableCommands() {
  return {
      {"prefilter", "build a prefiltered anisotropic table (seed 000): IN -o OUT.apt",
       RunPrefilter},
      {"info", "describe a texture file (.apt table, packed texture)", RunInfo},
  };
}

}  // namespace aperture
