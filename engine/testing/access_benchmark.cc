#include "testing/access_benchmark.h"

#include <time.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <random>
#include <span>

#include "absl/strings/str_cat.h"
#include "testing/quadtree_texture.h"
#include "texture/packed/apv_file.h"
#include "texture/packed/area_integral.h"
#include "texture/packed/packed_texture.h"
#include "texture/packed/run_index.h"

namespace aperture::packed {
namespace {

struct Points {
  std::vector<uint32_t> xs, ys;
};

Points RandomPoints(size_t n, uint32_t width, uint32_t height, uint64_t seed) {
  std::mt19937_64 rng(seed);
  Points p;
  p.xs.resize(n);
  p.ys.resize(n);
  for (size_t i = 0; i < n; ++i) {
    const uint64_t r = rng();
    p.xs[i] = static_cast<uint32_t>(((r & 0xFFFFFFFFu) * width) >> 32);
    p.ys[i] = static_cast<uint32_t>(((r >> 32) * height) >> 32);
  }
  return p;
}

// CPU time of this thread: other processes on a shared machine do not count against a method.
double ThreadSeconds() {
  timespec t;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// One timed pass of `read` over all points; keeps the fastest pass in `timing`.
template <typename Read>
void TimePass(const Points& p, AccessTiming& timing, Read read) {
  const double start = ThreadSeconds();
  uint64_t sum = 0;
  for (size_t i = 0; i < p.xs.size(); ++i) sum += read(p.xs[i], p.ys[i]);
  const double ns = (ThreadSeconds() - start) * 1e9 / static_cast<double>(p.xs.size());
  if (timing.ns_per_access == 0 || ns < timing.ns_per_access) timing.ns_per_access = ns;
  timing.checksum = sum;
}

// The same, through a batched reader: 4096 points per call.
template <typename ReadBatch>
void TimeBatches(const Points& p, AccessTiming& timing, ReadBatch read) {
  std::vector<uint32_t> colours(4096);
  const size_t count = p.xs.size();
  const double start = ThreadSeconds();
  uint64_t sum = 0;
  for (size_t begin = 0; begin < count; begin += colours.size()) {
    const size_t n = std::min(colours.size(), count - begin);
    read(std::span<const uint32_t>(p.xs.data() + begin, n),
         std::span<const uint32_t>(p.ys.data() + begin, n), std::span<uint32_t>(colours.data(), n));
    for (size_t i = 0; i < n; ++i) sum += colours[i];
  }
  const double ns = (ThreadSeconds() - start) * 1e9 / static_cast<double>(count);
  if (timing.ns_per_access == 0 || ns < timing.ns_per_access) timing.ns_per_access = ns;
  timing.checksum = sum;
}

// The integral of the bitmap over [x0, x1) x [y0, y1) (inside the texture), red channel.
double BitmapRedIntegral(const IndexedImage& image, double x0, double y0, double x1, double y1) {
  double sum = 0;
  for (uint32_t y = static_cast<uint32_t>(y0); y < y1; ++y) {
    const double wy = std::min<double>(y + 1, y1) - std::max<double>(y, y0);
    const uint8_t* row = &image.indices[size_t{y} * image.width];
    for (uint32_t x = static_cast<uint32_t>(x0); x < x1; ++x) {
      const double wx = std::min<double>(x + 1, x1) - std::max<double>(x, x0);
      sum += wx * wy * Channel(image.palette[row[x]], 0);
    }
  }
  return sum;
}

void BenchArea(const IndexedImage& image, const PackedTextureView& texture, uint64_t seed,
               PackedBenchReport& r) {
  constexpr size_t kQueries = 1'000'000;
  std::mt19937_64 rng(seed + 1);
  std::uniform_real_distribution<double> unit(0, 1);
  std::vector<double> rects(4 * kQueries);
  for (size_t i = 0; i < kQueries; ++i) {
    const double w = 1 + 15 * unit(rng), h = 1 + 15 * unit(rng);
    const double x0 = unit(rng) * (image.width - w), y0 = unit(rng) * (image.height - h);
    rects[4 * i] = x0;
    rects[4 * i + 1] = y0;
    rects[4 * i + 2] = x0 + std::min<double>(w, image.width);
    rects[4 * i + 3] = y0 + std::min<double>(h, image.height);
  }
  const AreaIntegrator area(texture);
  std::vector<double> packed_red(kQueries);
  double start = ThreadSeconds();
  for (size_t i = 0; i < kQueries; ++i)
    packed_red[i] =
        area.Integrate(rects[4 * i], rects[4 * i + 1], rects[4 * i + 2], rects[4 * i + 3])
            .channels[0];
  r.area_ns_packed = (ThreadSeconds() - start) * 1e9 / kQueries;
  start = ThreadSeconds();
  double worst = 0;
  for (size_t i = 0; i < kQueries; ++i) {
    const double red = BitmapRedIntegral(image, rects[4 * i], rects[4 * i + 1], rects[4 * i + 2],
                                         rects[4 * i + 3]);
    worst = std::max(worst, std::fabs(red - packed_red[i]) / std::max(1.0, red));
  }
  r.area_ns_bitmap = (ThreadSeconds() - start) * 1e9 / kQueries;
  r.area_queries = kQueries;
  r.area_max_relative_difference = worst;
}

}  // namespace

absl::StatusOr<PackedBenchReport> BenchPackedFile(const std::string& path, size_t accesses,
                                                  uint64_t seed, int rounds) {
  auto rgba = LoadRgba8Image(path);
  if (!rgba.ok()) return rgba.status();
  auto image = BuildPalette(*rgba);
  if (!image.ok())
    return absl::InvalidArgumentError(absl::StrCat(path, ": ", image.status().message()));
  rgba->texels = {};
  PackedBenchReport r;
  r.path = path;
  r.width = image->width;
  r.height = image->height;
  r.palette_size = image->palette.size();
  r.raw_bytes = uint64_t{r.width} * r.height;
  std::error_code ec;
  r.png_bytes = std::filesystem::file_size(path, ec);
  const auto start = std::chrono::steady_clock::now();
  auto packed_hilbert = PackTexture(*image, Curve::kHilbert);
  r.pack_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!packed_hilbert.ok()) return packed_hilbert.status();
  auto packed_morton = PackTexture(*image, Curve::kMorton);
  if (!packed_morton.ok()) return packed_morton.status();
  const std::vector<uint8_t> hilbert_apv = EncodeApv(packed_hilbert->view());
  const std::vector<uint8_t> morton_apv = EncodeApv(packed_morton->view());
  r.apv_hilbert_bytes = hilbert_apv.size();
  r.apv_morton_bytes = morton_apv.size();
  // The textures read below are the files loaded back, as a server holds them.
  const auto load_start = std::chrono::steady_clock::now();
  auto hilbert = DecodeApv(hilbert_apv);
  r.load_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - load_start).count();
  if (!hilbert.ok()) return hilbert.status();
  auto morton = DecodeApv(morton_apv);
  if (!morton.ok()) return morton.status();
  r.runs_hilbert = hilbert->view().run_count();
  r.runs_morton = morton->view().run_count();
  r.memory_hilbert_bytes = hilbert->view().byte_size();
  const QuadtreeTexture tree = QuadtreeTexture::Build(*image);
  r.quadtree_bytes = tree.byte_size();
  r.quadtree_nodes = tree.node_count();
  r.quadtree_leaves = tree.leaf_count();
  const RunIndex hilbert_index(hilbert->view());
  const RunIndex morton_index(morton->view());
  r.index_bytes = hilbert_index.byte_size();

  r.accesses = accesses;
  const Points p = RandomPoints(accesses, r.width, r.height, seed);
  const std::vector<uint8_t>& bitmap = image->indices;
  const std::vector<uint32_t>& palette = image->palette;
  const uint32_t width = r.width;
  const PackedTextureView& hv = hilbert->view();
  const PackedTextureView& mv = morton->view();
  r.timings = {{"raw bitmap"},
               {"binary search, Hilbert"},
               {"indexed search, Hilbert"},
               {"indexed batch, Hilbert"},
               {"binary search, Morton"},
               {"indexed search, Morton"},
               {"quadtree"},
               {"quadtree batch"}};
  // Rounds over all methods, the fastest pass of each kept: noise from other processes on a
  // shared machine only ever slows a pass down.
  for (int round = 0; round < rounds; ++round) {
    TimePass(p, r.timings[0],
             [&](uint32_t x, uint32_t y) { return palette[bitmap[size_t{y} * width + x]]; });
    TimePass(p, r.timings[1], [&](uint32_t x, uint32_t y) { return hv.ColorAt(x, y); });
    TimePass(p, r.timings[2], [&](uint32_t x, uint32_t y) { return hilbert_index.ColorAt(x, y); });
    TimeBatches(p, r.timings[3],
                [&](auto xs, auto ys, auto out) { hilbert_index.ColorsAt(xs, ys, out); });
    TimePass(p, r.timings[4], [&](uint32_t x, uint32_t y) { return mv.ColorAt(x, y); });
    TimePass(p, r.timings[5], [&](uint32_t x, uint32_t y) { return morton_index.ColorAt(x, y); });
    TimePass(p, r.timings[6], [&](uint32_t x, uint32_t y) { return tree.ColorAt(x, y); });
    TimeBatches(p, r.timings[7], [&](auto xs, auto ys, auto out) { tree.ColorsAt(xs, ys, out); });
  }
  BenchArea(*image, hv, seed, r);
  for (const AccessTiming& t : r.timings)
    if (t.checksum != r.timings[0].checksum)
      return absl::InternalError(
          absl::StrCat(path, ": ", t.method, " read different colours than the raw bitmap"));
  return r;
}

}  // namespace aperture::packed
