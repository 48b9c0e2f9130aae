// The measurements behind `aperture-bench packed` (seed 001, section 2.6, table 4): stored
// sizes and mean time per random texel access of the raw bitmap, the paper's binary search, the
// indexed search (run_index.h), one texel at a time and in batches, and the incomplete quadtree
// (one at a time and in lockstep batches), all on the same random points.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "absl/status/statusor.h"

namespace aperture::packed {

struct AccessTiming {
  std::string method;
  double ns_per_access = 0;
  uint64_t checksum = 0;  // sum of the colours read; equal for every method
};

struct PackedBenchReport {
  std::string path;
  uint32_t width = 0, height = 0;
  size_t palette_size = 0;
  size_t runs_hilbert = 0, runs_morton = 0, quadtree_nodes = 0, quadtree_leaves = 0;
  uint64_t raw_bytes = 0, png_bytes = 0, apv_hilbert_bytes = 0, apv_morton_bytes = 0;
  uint64_t memory_hilbert_bytes = 0, index_bytes = 0, quadtree_bytes = 0;
  double pack_seconds = 0;  // Hilbert packing, palette excluded
  double load_seconds = 0;  // decoding the Hilbert .apv (the timed textures are the decoded ones)
  size_t accesses = 0;      // per method and round
  std::vector<AccessTiming> timings;
  // Area sampling: random rectangles with fractional edges, sides uniform in [1, 16] texels,
  // integrated exactly on the Hilbert texture and by a weighted sum over the raw bitmap.
  size_t area_queries = 0;
  double area_ns_packed = 0, area_ns_bitmap = 0;
  double area_max_relative_difference = 0;
};

// Reads the image (palette built exactly, refused above 256 colours), packs it with both curves,
// builds the quadtree and times `accesses` random texel reads per method (the same points for
// every method), `rounds` times; each method's fastest round is reported. Times are this thread's
// CPU time.
absl::StatusOr<PackedBenchReport> BenchPackedFile(const std::string& path, size_t accesses,
                                                  uint64_t seed, int rounds = 3);

}  // namespace aperture::packed
