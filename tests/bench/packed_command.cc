// aperture-bench packed: seed 001's packed vector textures against a raw bitmap, PNG and an
// incomplete quadtree: sizes, random-access times and the area integral (section 2.6, table 4).
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "absl/status/status.h"
#include "bench/bench_commands.h"
#include "testing/access_benchmark.h"

namespace aperture::bench {
namespace {

using namespace packed;

int Fail(const char* command, const absl::Status& status) {
  std::fprintf(stderr, "aperture-bench %s: %s\n", command, std::string(status.message()).c_str());
  return 2;
}

int UsageError(const char* command, const char* usage, const std::string& problem) {
  std::fprintf(stderr, "aperture-bench %s: %s\nusage: aperture-bench %s\n", command,
               problem.c_str(), usage);
  return 2;
}

bool WantsHelp(int argc, char** argv, const char* usage, const char* about) {
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--help") == 0 || std::strcmp(argv[i], "-h") == 0) {
      std::printf("usage: aperture-bench %s\n\n%s\n", usage, about);
      return true;
    }
  }
  return false;
}

constexpr char kBenchUsage[] = "packed FILE... [--accesses N] [--rounds R] [--seed S]";

int RunPacked(int argc, char** argv) {
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
      if (i + 1 >= argc) return UsageError("packed", kBenchUsage, a + " needs a value");
      char* end = nullptr;
      const unsigned long long value = std::strtoull(argv[++i], &end, 10);
      if (end == argv[i] || *end != '\0')
        return UsageError("packed", kBenchUsage, a + " needs a whole number");
      (a == "--seed" ? seed : a == "--rounds" ? rounds : accesses) = value;
    } else if (!a.empty() && a[0] == '-') {
      return UsageError("packed", kBenchUsage, "unknown option " + a);
    } else {
      files.push_back(a);
    }
  }
  if (files.empty() || accesses == 0 || rounds == 0 || rounds > 100)
    return UsageError("packed", kBenchUsage,
                      "needs at least one file, accesses > 0 and rounds 1..100");
  for (const std::string& file : files) {
    auto r = BenchPackedFile(file, accesses, seed, static_cast<int>(rounds));
    if (!r.ok()) return Fail("packed", r.status());
    std::printf("%s: %u x %u, %zu colours\n", file.c_str(), r->width, r->height, r->palette_size);
    std::printf(
        "  bytes  raw %llu | PNG %llu | .apv Hilbert %llu (%zu runs) | .apv Morton %llu "
        "(%zu runs) | quadtree %llu (%zu nodes, %zu leaves)\n",
        (unsigned long long)r->raw_bytes, (unsigned long long)r->png_bytes,
        (unsigned long long)r->apv_hilbert_bytes, r->runs_hilbert,
        (unsigned long long)r->apv_morton_bytes, r->runs_morton,
        (unsigned long long)r->quadtree_bytes, r->quadtree_nodes, r->quadtree_leaves);
    std::printf("  memory Hilbert runs %llu + index %llu bytes; pack %.3f s\n",
                (unsigned long long)r->memory_hilbert_bytes, (unsigned long long)r->index_bytes,
                r->pack_seconds);
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
        "  targets: .apv %.2fx smaller than the quadtree (>= 3) | indexed %.2fx faster than "
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

std::vector<BenchCommand> PackedCommands() {
  return {{"packed", "sizes and random-access times: raw, PNG, .apv, quadtree", RunPacked}};
}

}  // namespace aperture::bench
