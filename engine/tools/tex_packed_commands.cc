// aperture-tex subcommands for packed vector textures (seed 001): pack, unpack, info,
// bench-packed.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "absl/status/status.h"
#include "testing/access_benchmark.h"
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

constexpr char kBenchUsage[] = "bench-packed FILE... [--accesses N] [--rounds R] [--seed S]";

int RunBench(int argc, char** argv) {
  if (WantsHelp(argc, argv, kBenchUsage,
                "For each palette image: bytes as raw 1-byte texels, PNG, .apv (Hilbert, Morton)\n"
                "and incomplete quadtree; mean ns per random texel access for the raw bitmap,\n"
                "binary search, indexed search and quadtree on the same random points\n"
                "(default 10,000,000 accesses per method and round, 3 rounds, the fastest round\n"
                "of each method reported; this thread's CPU time)."))
    return 0;
  std::vector<std::string> files;
  size_t accesses = 10'000'000;
  uint64_t seed = 1, rounds = 3;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--accesses" || a == "--seed" || a == "--rounds") {
      if (i + 1 >= argc) return UsageError("bench-packed", kBenchUsage, a + " needs a value");
      char* end = nullptr;
      const unsigned long long value = std::strtoull(argv[++i], &end, 10);
      if (end == argv[i] || *end != '\0')
        return UsageError("bench-packed", kBenchUsage, a + " needs a whole number");
      (a == "--seed" ? seed : a == "--rounds" ? rounds : accesses) = value;
    } else if (!a.empty() && a[0] == '-') {
      return UsageError("bench-packed", kBenchUsage, "unknown option " + a);
    } else {
      files.push_back(a);
    }
  }
  if (files.empty() || accesses == 0 || rounds == 0 || rounds > 100)
    return UsageError("bench-packed", kBenchUsage,
                      "needs at least one file, accesses > 0 and rounds 1..100");
  for (const std::string& file : files) {
    auto r = BenchPackedFile(file, accesses, seed, static_cast<int>(rounds));
    if (!r.ok()) return Fail("bench-packed", r.status());
    std::printf("%s: %u x %u, %zu colours\n", file.c_str(), r->width, r->height, r->palette_size);
    std::printf(
        "  bytes  raw %llu | PNG %llu | .apv Hilbert %llu (%zu runs) | .apv Morton %llu "
        "(%zu runs) | quadtree %llu (%zu nodes, %zu leaves)\n",
        (unsigned long long)r->raw_bytes, (unsigned long long)r->png_bytes,
        (unsigned long long)r->apv_hilbert_bytes, r->runs_hilbert,
        (unsigned long long)r->apv_morton_bytes, r->runs_morton,
        (unsigned long long)r->quadtree_bytes, r->quadtree_nodes, r->quadtree_leaves);
    std::printf("  memory Hilbert runs %llu + index %llu bytes; pack %.3f s; load .apv %.3f s\n",
                (unsigned long long)r->memory_hilbert_bytes, (unsigned long long)r->index_bytes,
                r->pack_seconds, r->load_seconds);
    std::printf("  quadtree / .apv Hilbert = %.2fx\n",
                double(r->quadtree_bytes) / double(r->apv_hilbert_bytes));
    // The quadtree's figure is its faster reader (one texel at a time or in lockstep batches).
    auto ns_of = [&](const std::string& method) {
      for (const AccessTiming& t : r->timings)
        if (t.method == method) return t.ns_per_access;
      return 0.0;
    };
    const double quadtree_ns = std::min(ns_of("quadtree"), ns_of("quadtree batch"));
    const double raw_ns = ns_of("raw bitmap");
    std::printf(
        "  random access, %zu points per method and round, fastest of %d rounds\n"
        "  (ns per access | fastest quadtree time / this | this / raw bitmap time):\n",
        r->accesses, static_cast<int>(rounds));
    for (const AccessTiming& t : r->timings)
      std::printf("    %-26s %8.1f ns   %5.2fx   %5.2fx\n", t.method.c_str(), t.ns_per_access,
                  quadtree_ns / t.ns_per_access, t.ns_per_access / raw_ns);
    const double indexed_ns = ns_of("indexed search, Hilbert");
    const double batch_ns = ns_of("indexed batch, Hilbert");
    std::printf(
        "  issue 4 bars: .apv %.2fx smaller than the quadtree (>= 3) | indexed %.2fx faster than "
        "the quadtree in batches, %.2fx one at a time (>= 6) | indexed %.2fx the raw bitmap's "
        "time (<= 2)\n",
        double(r->quadtree_bytes) / double(r->apv_hilbert_bytes), quadtree_ns / batch_ns,
        quadtree_ns / indexed_ns, indexed_ns / raw_ns);
    std::printf(
        "  area integral, %zu rectangles of 1..16 x 1..16 texels, fractional edges:\n"
        "    packed (Hilbert) %.1f ns | weighted sum over the raw bitmap %.1f ns | "
        "max relative difference %.1e\n",
        r->area_queries, r->area_ns_packed, r->area_ns_bitmap, r->area_max_relative_difference);
    std::fflush(stdout);
  }
  return 0;
}

}  // namespace

std::vector<TexCommand> PackedTextureCommands() {
  return {
      {"pack", "pack a palette image into a packed vector texture (.apv)", RunPack},
      {"unpack", "unpack an .apv file into an image", RunUnpack},
      {"info", "describe a texture file (.apv)", RunInfo},
      {"bench-packed", "sizes and random-access times: raw, PNG, .apv, quadtree", RunBench},
  };
}

}  // namespace aperture
