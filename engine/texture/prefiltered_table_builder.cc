#include "texture/prefiltered_table_builder.h"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <spdlog/spdlog.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstring>
#include <functional>
#include <span>

#include "absl/strings/str_cat.h"
#include "base/stopwatch.h"
#include "texture/table_column_kernels.h"

namespace aperture {
namespace {

// Double-precision RGBA accumulator.
struct Sum4 {
  double r = 0, g = 0, b = 0, a = 0;
  void Add(const Rgba& c, double w) { r += c.r * w, g += c.g * w, b += c.b * w, a += c.a * w; }
  void Sub(const Rgba& c) { r -= c.r, g -= c.g, b -= c.b, a -= c.a; }
  Rgba Scaled(double s) const {
    return {static_cast<float>(r * s), static_cast<float>(g * s), static_cast<float>(b * s),
            static_cast<float>(a * s)};
  }
};

uint8_t Quantize(float v) {
  // std::lround for x >= 0 without the libm call: x - trunc(x) is exact.
  const float x = std::clamp(v, 0.0f, 1.0f) * 255.0f;
  const int i = static_cast<int>(x);
  return static_cast<uint8_t>(i + (x - static_cast<float>(i) >= 0.5f ? 1 : 0));
}

void StoreTexel(uint8_t* dst, const Rgba& c) {
  dst[0] = Quantize(c.r), dst[1] = Quantize(c.g), dst[2] = Quantize(c.b), dst[3] = Quantize(c.a);
}

// The table needs a square power of two of at least 2 x 2.
Image SquarePowerOfTwo(const Image& image) {
  int size = 2;
  while (size < std::max(image.width(), image.height())) size *= 2;
  if (image.width() == size && image.height() == size) return image;
  spdlog::info("prefiltered table: resampling {}x{} to {}x{} (OpenImageIO default filter)",
               image.width(), image.height(), size, size);
  OIIO::ImageSpec src_spec(image.width(), image.height(), 4, OIIO::TypeDesc::FLOAT);
  OIIO::ImageBuf src(src_spec, const_cast<Rgba*>(image.texels().data()));
  OIIO::ROI roi(0, size, 0, size, 0, 1, 0, 4);
  OIIO::ImageBuf dst = OIIO::ImageBufAlgo::resize(src, "", 0.0f, roi);
  Image out(size, size);
  dst.get_pixels(roi, OIIO::TypeDesc::FLOAT, out.texels().data());
  return out;
}

// Texel (major, minor) of the source for one orientation: tilt U reads (x = major, y = minor),
// tilt V the transpose.
const Rgba& SourceTexel(const Image& src, bool transposed, int major, int minor) {
  return transposed ? src.at(minor, major) : src.at(major, minor);
}

// First pass, the minor axis: the average of line c (constant major index) over the minor
// interval [k - L, k + L), by a running window down blocks of lines; piecewise linear in k between
// integers. Stored as 16-bit fixed point (1 = 65535), so that the second pass streams through
// half the bytes of floats, at g[MinorIndex(N, L, c, k)]: line by line, and within a line by the
// residue of k mod L, then k / L. The sheared lines of the second pass, L apart in k, then read
// consecutive entries.
using Packed = PackedTexel;

inline size_t MinorIndex(int N, int L, int c, int k) {
  return static_cast<size_t>(c) * N + static_cast<size_t>(k % L) * (N / L) + k / L;
}

void MinorBoxAverage(const Image& src, bool transposed, int L, std::vector<Packed>& g) {
  const int N = src.width();
  constexpr int kBlock = 16;
  g.resize(static_cast<size_t>(N) * N);
  const double scale = 65535.0 / (2.0 * L);
  auto pack = [](double v) {
    const double x = std::clamp(v, 0.0, 65535.0);  // std::lround for x >= 0, as in Quantize
    const int i = static_cast<int>(x);
    return static_cast<uint16_t>(i + (x - static_cast<double>(i) >= 0.5 ? 1 : 0));
  };
  tbb::parallel_for(0, (N + kBlock - 1) / kBlock, [&](int block) {
    const int c0 = block * kBlock, c1 = std::min(N, c0 + kBlock);
    Sum4 window[kBlock];
    for (int c = c0; c < c1; ++c)
      for (int m = -L; m < L; ++m)
        window[c - c0].Add(SourceTexel(src, transposed, c, m & (N - 1)), 1.0);
    for (int k = 0; k < N; ++k) {
      for (int c = c0; c < c1; ++c) {
        Sum4& w = window[c - c0];
        g[MinorIndex(N, L, c, k)] = {pack(w.r * scale), pack(w.g * scale), pack(w.b * scale),
                                     pack(w.a * scale)};
        w.Add(SourceTexel(src, transposed, c, (k + L) & (N - 1)), 1.0);
        w.Sub(SourceTexel(src, transposed, c, (k - L) & (N - 1)));
      }
    }
  });
}

struct CopyJob {
  int N = 0;
  int L = 1;      // half-thickness (texels)
  double H = 1;   // half-extent along the major axis (texels)
  double tg = 0;  // slope of the long side: d(minor) / d(major)
  // The line's shift along the minor axis (texels): an end tilt of L = 1 is swept twice, at
  // -1/4 and +1/4, and the two averaged (WriteCopy).
  double minor_shift = 0;
  int major = 1;  // resolution along the major axis
  bool transposed = false;
  uint8_t* out = nullptr;  // RGBA8, row-major in (u, v)
};

// Second pass, along the sheared lines (seed 000: the box parallelogram). Output texel (p, q)
// has its centre at ((p + 0.5) N / major, (q + 0.5) L); all centres lie on the N / L lines
// minor = (r + 0.5) L + tg (major + 0.5) (tg (p + 0.5) N / major is a multiple of L for every
// tilt of the table: N / major = lambda L, and lambda tg is an even integer, 2 (2k + 1) - lambda
// for seed 000's tilts and +-lambda for the ends), so per line one running sum over the N
// columns serves every output on it.
// The windows [centre - H, centre + H] start and end on multiples of `step` columns, so only
// those running sums are kept. A line leaving the period at major = N re-enters at major = 0
// as line r + tg N / L.
struct CopySweep {
  CopyJob job;
  int step = 1;
  std::vector<int> k_base;    // line r passes column c between minor rows k_base[c] + r L
  std::vector<float> weight;  // and the next one, with this weight towards the next
  // prefix[s * rows + r]: line r's sum over the columns [0, s step), in the group's buffer.
  Rgba* prefix = nullptr;
};

CopySweep PrepareSweep(const CopyJob& job) {
  const int N = job.N, L = job.L;
  CopySweep s;
  s.job = job;
  s.step = job.H < 2 ? 1 : std::max(1, std::min(static_cast<int>(job.H) / 2, N / 4));
  // Line r passes column c at minor = (r + 0.5) L + tg (c + 0.5): lines differ by whole multiples
  // of L, so the interpolation weights along c are the same for every line, and lines r, r + 1,
  // ... read consecutive entries of g (MinorIndex) from row k_base[c] + r L on.
  s.k_base.resize(N);
  s.weight.resize(N);
  for (int c = 0; c < N; ++c) {
    const double y = 0.5 * L + job.tg * (c + 0.5) + job.minor_shift, fy = std::floor(y);
    s.k_base[c] = static_cast<int>(fy);
    s.weight[c] = static_cast<float>(y - fy);
  }
  return s;
}

size_t PrefixSize(const CopySweep& s) {
  return static_cast<size_t>(s.job.N / s.step + 1) * (s.job.N / s.job.L);
}

// Lines per block of the sweep (see SweepCopies): 8 KiB of running sums. A 4096 x 4096 build
// on 2 threads took 25.8-27.3 s with blocks of 512 and 1024 lines and with none (one block of
// the band's 2048 lines).
constexpr int kBlock = 512;

// Columns between two stop tests inside a sweep: a group at L = 1 of a 2048 x 2048 table takes
// a few tenths of a second, more on a loaded machine, and a load's deadline must stop it sooner.
constexpr int kStopColumns = 256;

// The running sums of several copies with the same L (and axis, so the same g) at once: each
// column of g is read from memory once for all of them, not once per copy. `stop` (may be empty)
// is asked by each band every kStopColumns columns; after a yes, `stopped` is set and the sums
// are left unfinished.
void SweepCopies(std::span<CopySweep> copies, const std::vector<Packed>& g, int N, int L,
                 const std::function<bool()>& stop, std::atomic<bool>& stopped) {
  const int rows = N / L;
  // N, L and rows are powers of two: residues and quotients by masks and shifts.
  int log2_l = 0;
  while ((1 << log2_l) < L) ++log2_l;
  const int n_mask = N - 1, l_mask = L - 1, rows_mask = rows - 1;
  const AddColumnFn add_column = BestAddColumn();
  // One band of lines per thread: the work per column and copy outside the kernel is then
  // spread over the most lines. A 4096 x 4096 build on 2 threads took 35, 34, 33 and 30 s with
  // bands of 256, 512, 1024 and 2048 lines.
  const int threads = std::max(1, tbb::this_task_arena::max_concurrency());
  const int band_lines = std::max(16, (rows + threads - 1) / threads);
  tbb::parallel_for(0, (rows + band_lines - 1) / band_lines, [&](int band) {
    const int r0 = band * band_lines, r1 = std::min(rows, r0 + band_lines);
    const size_t width = 4 * static_cast<size_t>(r1 - r0);
    std::vector<float> acc(width * copies.size(), 0.0f);
    for (CopySweep& s : copies)  // s = 0: the empty sums
      std::fill(s.prefix + r0, s.prefix + r1, Rgba{});
    // Chunks of kChunk columns, copy after copy, and within them blocks of kBlock lines: a
    // block's sums stay in L1 over the chunk's columns, a copy's over the chunk, and the chunk of
    // g over the copies (each line's sum still grows column by column).
    constexpr int kChunk = 16;
    struct ColumnRead {
      const Packed* a;  // line r reads a[(qa0 + r) mod rows] and b[(qb0 + r) mod rows]
      const Packed* b;
      int qa0, qb0;
      float weight;
      bool keep;  // the sums after this column are a prefix the copy's texels read
    };
    ColumnRead reads[kChunk];
    for (int c0 = 0; c0 < N; c0 += kChunk) {
      if (c0 % kStopColumns == 0 && stop) {
        if (stopped.load(std::memory_order_relaxed)) return;
        if (stop()) {
          stopped.store(true, std::memory_order_relaxed);
          return;
        }
      }
      const int chunk = std::min(kChunk, N - c0);
      for (size_t q = 0; q < copies.size(); ++q) {
        CopySweep& s = copies[q];
        float* sums = &acc[q * width];
        for (int k = 0; k < chunk; ++k) {
          // Line r reads rows k_base + r L (residue rho_a, quotient qa0 + r) and the next one.
          const int c = c0 + k;
          const int kb = s.k_base[c] & n_mask;
          const int rho_a = kb & l_mask, qa0 = kb >> log2_l;
          const bool next_in_residue = rho_a + 1 < L;
          const int rho_b = next_in_residue ? rho_a + 1 : 0, qb0 = next_in_residue ? qa0 : qa0 + 1;
          reads[k] = {
              &g[MinorIndex(N, L, c, rho_a)], &g[MinorIndex(N, L, c, rho_b)], qa0, qb0, s.weight[c],
              ((c + 1) & (s.step - 1)) == 0};
        }
        for (int b0 = r0; b0 < r1; b0 += kBlock) {
          const int b1 = std::min(r1, b0 + kBlock);
          for (int k = 0; k < chunk; ++k) {
            const ColumnRead& rd = reads[k];
            for (int r = b0; r < b1;) {  // in runs that end where a quotient wraps past rows
              const int ia = (rd.qa0 + r) & rows_mask, ib = (rd.qb0 + r) & rows_mask;
              const int n = std::min({b1 - r, rows - ia, rows - ib});
              add_column(sums + 4 * static_cast<size_t>(r - r0), rd.a + ia, rd.b + ib, n,
                         rd.weight);
              r += n;
            }
            if (rd.keep)
              std::memcpy(static_cast<void*>(
                              &s.prefix[static_cast<size_t>((c0 + k + 1) / s.step) * rows + b0]),
                          sums + 4 * static_cast<size_t>(b0 - r0),
                          sizeof(float) * 4 * static_cast<size_t>(b1 - b0));
          }
        }
      }
    }
  });
}

// Whether a copy is swept twice. The sweep takes each texel column's band at the column's centre
// (the midpoint rule along the major axis), exact where the band's box sum is linear across the
// column. Its kinks lie where the band's edges cross texel rows; for L = 1 and tg = +-1 (the end
// tilts) one always lies mid-column, which misses (g[m-1] - 2 g[m] + g[m+1]) / 8 of the rows'
// sums. Two sweeps with the line shifted by -1/4 and +1/4 sample each half-column at its centre,
// where the sum is linear: exact. (For L >= 2 the kinks lie on column edges, and seed 000's tilts
// move the band by under a row across a column.)
bool SweptTwice(const CopyEntry& e) { return e.log2_l == 0 && std::abs(e.tg) == 1.0f; }

// The copy's texels from its running sums: each a window of 2H columns along its line, averaged
// with the same window of `twin` when the copy is swept twice.
void WriteCopy(const CopySweep& s, const CopySweep* twin) {
  const CopyJob& job = s.job;
  const int N = job.N, L = job.L, rows = N / L, step = s.step;
  const int sx = N / job.major;
  const long wrap = std::lround(job.tg * N / L);
  // N, rows = N / L and step are powers of two: wrap and divide by masks and shifts.
  int log2_n = 0, log2_step = 0;
  while ((1 << log2_n) < N) ++log2_n;
  while ((1 << log2_step) < step) ++log2_step;
  auto row_of = [&](long r) { return static_cast<int>(r & static_cast<long>(rows - 1)); };
  // Running sum along the extended line r from column 0 to column c (a multiple of `step`), of
  // each sweep.
  auto ext_one = [&](const Rgba* prefix, int r, long c, Sum4& acc, double sign) {
    const long k = c >= 0 ? c >> log2_n : -((-c + N - 1) >> log2_n);
    const long cc = c - k * N;
    const size_t last = static_cast<size_t>(N / step);
    for (long kk = 0; kk < k; ++kk) acc.Add(prefix[last * rows + row_of(r + kk * wrap)], sign);
    for (long kk = k; kk < 0; ++kk) acc.Add(prefix[last * rows + row_of(r + kk * wrap)], -sign);
    acc.Add(prefix[static_cast<size_t>(cc >> log2_step) * rows + row_of(r + k * wrap)], sign);
  };
  auto ext = [&](int r, long c, Sum4& acc, double sign) {
    ext_one(s.prefix, r, c, acc, sign);
    if (twin) ext_one(twin->prefix, r, c, acc, sign);
  };
  // Sums are in units of 1 / 65535.
  const double inv = 1.0 / (2.0 * job.H * 65535.0 * (twin ? 2.0 : 1.0));
  tbb::parallel_for(tbb::blocked_range<int>(0, rows, 4), [&](const tbb::blocked_range<int>& rr) {
    for (int r = rr.begin(); r != rr.end(); ++r) {
      for (int p = 0; p < job.major; ++p) {
        const double cx = (p + 0.5) * sx;
        const int q = row_of(r + std::lround(job.tg * cx / L));
        const double lo = cx - job.H, hi = cx + job.H;
        const long c_lo = static_cast<long>(std::ceil(lo)),
                   c_hi = static_cast<long>(std::floor(hi));
        Sum4 acc;
        ext(r, c_hi, acc, 1.0);
        ext(r, c_lo, acc, -1.0);
        if (c_lo > lo) {  // partial end columns (H = 1, step 1 only)
          ext(r, c_lo, acc, c_lo - lo);
          ext(r, c_lo - 1, acc, -(c_lo - lo));
        }
        if (hi > c_hi) {
          ext(r, c_hi + 1, acc, hi - c_hi);
          ext(r, c_hi, acc, -(hi - c_hi));
        }
        const size_t index = job.transposed ? static_cast<size_t>(p) * rows + q
                                            : static_cast<size_t>(q) * job.major + p;
        StoreTexel(job.out + 4 * index, acc.Scaled(inv));
      }
    }
  });
}

absl::Status StoppedPartBuilt(int N) {
  return absl::CancelledError(
      absl::StrCat("the seed 000 table of a ", N, "x", N, " texture was stopped part-built"));
}

}  // namespace

absl::StatusOr<TableBlock> BuildPrefilteredTable(const Image& image,
                                                 const TableBuildOptions& options) {
  if (image.empty()) return absl::InvalidArgumentError("prefiltered table: empty image");
  // Checked before resampling: a 1 x 65536 image would otherwise become 65536 x 65536 first.
  if (std::max(image.width(), image.height()) > (1 << kTableMaxLog2Size))
    return absl::InvalidArgumentError(
        absl::StrCat("prefiltered table: a ", image.width(), "x", image.height(),
                     " image needs a larger table than the limit of ", 1 << kTableMaxLog2Size, "x",
                     1 << kTableMaxLog2Size));
  const Stopwatch timer;
  const Image src = SquarePowerOfTwo(image);
  const int N = src.width();
  int n = 0;
  while ((1 << n) < N) ++n;

  // Directory: the base, then cells (j, i), each U tilts then V tilts.
  std::vector<CopyEntry> dir;
  dir.push_back(
      {kBaseCell, kBaseCell, TiltAxis::kNone, 0, 0, 0.0f, 1, uint32_t(N), uint32_t(N), 0});
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i < n; ++i) {
      const CellShape s = TableCellShape(n, j, i);
      const uint32_t copies = CellCopies(s.lambda), tilts = TiltsPerAxis(s.lambda);
      for (uint32_t c = 0; c < copies; ++c) {
        CopyEntry e{};
        e.log2_l = static_cast<uint8_t>(j);
        e.log2_ratio = static_cast<uint8_t>(i);
        e.lambda = s.lambda;
        const bool tilt_u = s.lambda == 1 || c < tilts;
        e.axis = s.lambda == 1 ? TiltAxis::kNone : (tilt_u ? TiltAxis::kU : TiltAxis::kV);
        e.tilt_index = c % tilts;
        e.tg = TiltTangent(s.lambda, e.tilt_index);
        e.width = tilt_u ? s.major : s.minor;
        e.height = tilt_u ? s.minor : s.major;
        dir.push_back(e);
      }
    }
  }
  TableHeader h{};
  std::memcpy(h.magic, kTableMagic, sizeof(h.magic));
  h.version = kTableVersion;
  h.header_bytes = sizeof(TableHeader);
  h.log2_size = static_cast<uint32_t>(n);
  h.texel_format = kTexelRgba8;
  h.copy_count = static_cast<uint32_t>(dir.size());
  h.directory_offset = sizeof(TableHeader);
  h.data_offset = (h.directory_offset + dir.size() * sizeof(CopyEntry) + 63) / 64 * 64;
  uint64_t offset = h.data_offset;
  for (CopyEntry& e : dir) {
    e.offset = offset;
    offset += uint64_t{e.width} * e.height * 4;
  }
  h.total_bytes = offset;
  h.source_width = static_cast<uint32_t>(image.width());
  h.source_height = static_cast<uint32_t>(image.height());

  TableBlock block;
  // The block is zero-filled a slice at a time, asking `stop` between slices: the first touch of
  // a 2048 x 2048 texture's 300 MB takes most of a second on some machines, longer than a load's
  // deadline may allow.
  block.bytes.reserve(h.total_bytes);
  constexpr size_t kZeroSlice = size_t{16} << 20;
  while (block.bytes.size() < h.total_bytes) {
    if (options.stop && options.stop()) return StoppedPartBuilt(N);
    block.bytes.resize(std::min<size_t>(h.total_bytes, block.bytes.size() + kZeroSlice));
  }
  std::byte* base = block.bytes.data();
  uint8_t* texels = reinterpret_cast<uint8_t*>(base);
  tbb::task_arena arena(options.threads > 0 ? options.threads : tbb::task_arena::automatic);
  bool stopped = false;
  arena.execute([&] {
    tbb::parallel_for(0, N, [&](int y) {  // the base copy: the texture itself
      for (int x = 0; x < N; ++x)
        StoreTexel(texels + dir[0].offset + 4 * (static_cast<size_t>(y) * N + x), src.at(x, y));
    });
    std::vector<Packed> g_u, g_v;
    int filtered_j = -1;
    // Groups of up to kGroup consecutive copies of one cell and axis (the directory is ordered
    // by j, then i, then axis), swept together. A 4096 x 4096 build took 42, 38, 34 and 35 s
    // with groups of 16, 32, 64 and 128 copies (2 threads).
    constexpr size_t kGroup = 64;
    std::vector<CopySweep> group;
    std::vector<Rgba> prefixes;
    // Work of a copy: its lines times the N columns, N^2 / L.
    auto work_of = [&](const CopyEntry& e) { return static_cast<double>(N >> e.log2_l); };
    double total_work = 0, work_done = 0;
    for (size_t d = 1; d < dir.size(); ++d) total_work += work_of(dir[d]);
    for (size_t d = 1; d < dir.size();) {
      if (options.stop && options.stop()) {
        stopped = true;
        return;
      }
      const CopyEntry& first = dir[d];
      const int j = first.log2_l, i = first.log2_ratio;
      if (j != filtered_j) {
        MinorBoxAverage(src, false, 1 << j, g_u);
        MinorBoxAverage(src, true, 1 << j, g_v);
        filtered_j = j;
      }
      std::vector<CopyJob> jobs;
      for (; d < dir.size() && jobs.size() + 2 <= kGroup; ++d) {
        const CopyEntry& e = dir[d];
        if (e.log2_l != first.log2_l || e.log2_ratio != first.log2_ratio || e.axis != first.axis)
          break;
        CopyJob job;
        job.N = N;
        job.L = 1 << j;
        job.H = std::ldexp(1.0, i + j);
        job.tg = e.tg;
        job.transposed = e.axis == TiltAxis::kV;
        job.major = static_cast<int>(job.transposed ? e.height : e.width);
        job.out = texels + e.offset;
        if (SweptTwice(e)) {  // this sweep, then its twin at +1/4 next in the group
          job.minor_shift = -0.25;
          jobs.push_back(job);
          job.minor_shift = 0.25;
        }
        jobs.push_back(job);
        work_done += work_of(e);
      }
      group.clear();  // frees the last group's sums first
      group.resize(jobs.size());
      tbb::parallel_for(size_t{0}, jobs.size(),
                        [&](size_t q) { group[q] = PrepareSweep(jobs[q]); });
      // One buffer for the groups' sums, grown when needed and reused: every entry is written
      // before it is read, and fresh pages for each group cost more than the sums (page faults).
      size_t entries = 0;
      for (const CopySweep& c : group) entries += PrefixSize(c);
      if (entries > prefixes.size()) {
        prefixes.clear();
        prefixes.shrink_to_fit();
        prefixes.resize(entries);
      }
      entries = 0;
      for (CopySweep& c : group) {
        c.prefix = prefixes.data() + entries;
        entries += PrefixSize(c);
      }
      std::atomic<bool> sweep_stopped{false};
      SweepCopies(group, first.axis == TiltAxis::kV ? g_v : g_u, N, 1 << j, options.stop,
                  sweep_stopped);
      if (sweep_stopped.load()) {
        stopped = true;
        return;
      }
      for (size_t q = 0; q < group.size(); ++q) {
        const bool twice = group[q].job.minor_shift < 0;  // its twin follows it
        WriteCopy(group[q], twice ? &group[q + 1] : nullptr);
        if (twice) ++q;
      }
      if (options.progress) options.progress(d == dir.size() ? 1.0 : work_done / total_work);
    }
  });
  if (stopped) return StoppedPartBuilt(N);
  const double seconds = timer.Seconds();
  h.build_milliseconds = static_cast<uint32_t>(std::lround(seconds * 1000.0));
  std::memcpy(base, &h, sizeof(h));
  std::memcpy(base + h.directory_offset, dir.data(), dir.size() * sizeof(CopyEntry));
  return block;
}

}  // namespace aperture
