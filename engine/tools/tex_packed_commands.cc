// aperture-tex subcommands for packed vector textures (seed 001): pack, unpack, info.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "absl/status/status.h"
#include "texture/packed/apv_file.h"
#include "texture/packed/packed_texture.h"
#include "texture/packed/palette.h"
#include "texture/packed/rgba8_image.h"
#include "tools/tex_commands.h"

namespace aperture {
namespace {

using namespace packed;

int Fail(const char* command, const absl::Status& status) {
  std::fprintf(stderr, "aperture-tex %s: %s\n", command, std::string(status.message()).c_str());
  return 2;
}

int UsageError(const char* command, const char* usage, const std::string& problem) {
  std::fprintf(stderr, "aperture-tex %s: %s\nusage: aperture-tex %s\n", command, problem.c_str(),
               usage);
  return 2;
}

bool WantsHelp(int argc, char** argv, const char* usage, const char* about) {
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--help") == 0 || std::strcmp(argv[i], "-h") == 0) {
      std::printf("usage: aperture-tex %s\n\n%s\n", usage, about);
      return true;
    }
  }
  return false;
}

constexpr char kPackUsage[] =
    "pack IN -o OUT.apv [--curve hilbert|morton] [--quantize] [--apv-version 1|2]";

int RunPack(int argc, char** argv) {
  if (WantsHelp(argc, argv, kPackUsage,
                "Packs a palette image (<= 256 colours; --quantize reduces more to 256) into runs\n"
                "along a Hilbert (default) or Morton curve, written as an .apv file (seed 001):\n"
                "version 2 (default) with its runs compressed by zstd, version 1 uncompressed."))
    return 0;
  std::string in, out, curve_name = "hilbert";
  bool quantize = false;
  ApvWriteOptions write;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if ((a == "-o" || a == "--curve" || a == "--apv-version") && i + 1 >= argc)
      return UsageError("pack", kPackUsage, a + " needs a value");
    if (a == "-o") {
      out = argv[++i];
    } else if (a == "--apv-version") {
      const std::string v = argv[++i];
      if (v != "1" && v != "2")
        return UsageError("pack", kPackUsage, "--apv-version is 1 or 2, not '" + v + "'");
      write.version = v == "1" ? kApvVersionPlain : kApvVersionZstd;
    } else if (a == "--curve") {
      curve_name = argv[++i];
    } else if (a == "--quantize") {
      quantize = true;
    } else if (!a.empty() && a[0] == '-') {
      return UsageError("pack", kPackUsage, "unknown option " + a);
    } else if (in.empty()) {
      in = a;
    } else {
      return UsageError("pack", kPackUsage, "more than one input file");
    }
  }
  if (in.empty() || out.empty()) return UsageError("pack", kPackUsage, "needs IN and -o OUT.apv");
  auto curve = ParseCurve(curve_name);
  if (!curve.ok()) return Fail("pack", curve.status());
  auto rgba = LoadRgba8Image(in);
  if (!rgba.ok()) return Fail("pack", rgba.status());
  auto image = BuildPalette(*rgba, quantize);
  if (!image.ok())
    return Fail("pack",
                absl::InvalidArgumentError(in + ": " + std::string(image.status().message())));
  auto texture = PackTexture(*image, *curve);
  if (!texture.ok()) return Fail("pack", texture.status());
  const std::vector<uint8_t> bytes = EncodeApv(texture->view(), write);
  if (absl::Status s = WriteFileBytes(out, bytes); !s.ok()) return Fail("pack", s);
  std::printf("%s: %ux%u, %zu colours, %s curve, %zu runs, %zu bytes (%.4f bits per texel)\n",
              out.c_str(), image->width, image->height, image->palette.size(), CurveName(*curve),
              texture->view().run_count(), bytes.size(),
              8.0 * bytes.size() / (double(image->width) * image->height));
  return 0;
}

constexpr char kUnpackUsage[] = "unpack IN.apv -o OUT.png";

int RunUnpack(int argc, char** argv) {
  if (WantsHelp(argc, argv, kUnpackUsage,
                "Unpacks every texel of an .apv file into an image (any format OpenImageIO "
                "writes)."))
    return 0;
  std::string in, out;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "-o") {
      if (i + 1 >= argc) return UsageError("unpack", kUnpackUsage, "-o needs a value");
      out = argv[++i];
    } else if (!a.empty() && a[0] == '-') {
      return UsageError("unpack", kUnpackUsage, "unknown option " + a);
    } else if (in.empty()) {
      in = a;
    } else {
      return UsageError("unpack", kUnpackUsage, "more than one input file");
    }
  }
  if (in.empty() || out.empty())
    return UsageError("unpack", kUnpackUsage, "needs IN.apv and -o OUT");
  auto texture = ReadApvFile(in);
  if (!texture.ok()) return Fail("unpack", texture.status());
  if (absl::Status s = WriteRgba8Image(ExpandPalette(UnpackTexture(texture->view())), out); !s.ok())
    return Fail("unpack", s);
  return 0;
}

constexpr char kInfoUsage[] = "info IN.apv";

int RunInfo(int argc, char** argv) {
  if (argc != 2 || argv[1][0] == '-') {
    if (WantsHelp(argc, argv, kInfoUsage, "Describes a packed vector texture (.apv).")) return 0;
    return 3;  // not ours to judge: the other family's `info` may know these arguments
  }
  auto bytes = ReadFileBytes(argv[1]);
  if (!bytes.ok()) return Fail("info", bytes.status());
  if (!LooksLikeApv(*bytes)) return 3;
  auto texture = DecodeApv(*bytes);
  if (!texture.ok()) return Fail("info", texture.status());
  const PackedTextureView& v = texture->view();
  const double texels = double(v.width()) * v.height();
  std::printf("%s: packed vector texture (.apv version %u%s)\n", argv[1], ApvVersionOf(*bytes),
              ApvVersionOf(*bytes) == kApvVersionZstd ? ", runs compressed by zstd" : "");
  std::printf("  size        %u x %u texels\n", v.width(), v.height());
  std::printf("  curve       %s, order %d (%u x %u enclosing square)\n", CurveName(v.curve()),
              v.order(), 1u << v.order(), 1u << v.order());
  std::printf("  palette     %zu colours\n", v.palette().size());
  std::printf("  runs        %zu (%.1f texels per run)\n", v.run_count(), texels / v.run_count());
  std::printf("  file        %zu bytes, %.4f bits per texel\n", bytes->size(),
              8.0 * bytes->size() / texels);
  std::printf("  in memory   %zu bytes\n", v.byte_size());
  for (size_t i = 0; i < v.palette().size(); ++i) {
    const uint32_t c = v.palette()[i];
    std::printf("  colour %3zu  #%02X%02X%02X alpha %u\n", i, Channel(c, 0), Channel(c, 1),
                Channel(c, 2), Channel(c, 3));
  }
  return 0;
}

}  // namespace

std::vector<TexCommand> PackedTextureCommands() {
  return {
      {"pack", "pack a palette image into a packed vector texture (.apv)", RunPack},
      {"unpack", "unpack an .apv file into an image", RunUnpack},
      {"info", "describe a texture file (.apv)", RunInfo},
  };
}

}  // namespace aperture
