#include "texture/summed_area_table.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"

namespace aperture {
namespace {

int Wrap(int i, int n) { return ((i % n) + n) % n; }

// One axis of [lo, hi] cut at the period borders: pieces within [0, period], each with how many
// times it occurs (the whole periods in the middle are one piece counted n times).
struct Piece {
  double lo, hi, count;
};

// The block's header (ToBytes / View).
constexpr char kMagic[8] = {'A', 'P', 'S', 'A', 'T', 'v', '1', 0};
struct BlockHeader {
  char magic[8];
  uint32_t version;
  int32_t width, height, channels;
  uint32_t reserved[2];
};
static_assert(sizeof(BlockHeader) == 32);

int SplitPeriods(double lo, double hi, double period, Piece out[3]) {
  if (!(hi > lo)) return 0;
  const double p0 = std::floor(lo / period), p1 = std::floor(hi / period);
  if (p0 == p1) {
    out[0] = {lo - p0 * period, hi - p0 * period, 1};
    return 1;
  }
  int n = 0;
  out[n++] = {lo - p0 * period, period, 1};
  if (p1 - p0 > 1) out[n++] = {0, period, p1 - p0 - 1};
  if (hi > p1 * period) out[n++] = {0, hi - p1 * period, 1};
  return n;
}

}  // namespace

SummedAreaTable::SummedAreaTable(const Image& image, int channels)
    : width_(image.width()), height_(image.height()), channels_(std::clamp(channels, 1, 4)) {
  const int w2 = width_ + 2, h2 = height_ + 2;
  tables_.assign(static_cast<size_t>(kTables) * w2 * h2 * channels_, 0.0);
  auto at = [&](int table, int i, int j) {
    return &tables_[((static_cast<size_t>(j + 1) * w2 + (i + 1)) * kTables + table) * channels_];
  };
  // The samples, wrapped one texel past every border.
  for (int j = -1; j <= height_; ++j)
    for (int i = -1; i <= width_; ++i) {
      const Rgba& t = image.at(Wrap(i, width_), Wrap(j, height_));
      const float v[4] = {t.r, t.g, t.b, t.a};
      double* d = at(kT, i, j);
      for (int c = 0; c < channels_; ++c) d[c] = v[c];
    }
  // Trapezoid prefix sums from c_-1: QT along x (per row), TQ along y (per column), QQ along x
  // of TQ. Entry -1 stays 0.
  for (int j = -1; j <= height_; ++j)
    for (int i = -1; i < width_; ++i) {
      const double *t0 = at(kT, i, j), *t1 = at(kT, i + 1, j), *q0 = at(kQT, i, j);
      double* q1 = at(kQT, i + 1, j);
      for (int c = 0; c < channels_; ++c) q1[c] = q0[c] + 0.5 * (t0[c] + t1[c]);
    }
  for (int j = -1; j < height_; ++j)
    for (int i = -1; i <= width_; ++i) {
      const double *t0 = at(kT, i, j), *t1 = at(kT, i, j + 1), *q0 = at(kTQ, i, j);
      double* q1 = at(kTQ, i, j + 1);
      for (int c = 0; c < channels_; ++c) q1[c] = q0[c] + 0.5 * (t0[c] + t1[c]);
    }
  for (int j = -1; j <= height_; ++j)
    for (int i = -1; i < width_; ++i) {
      const double *t0 = at(kTQ, i, j), *t1 = at(kTQ, i + 1, j), *q0 = at(kQQ, i, j);
      double* q1 = at(kQQ, i + 1, j);
      for (int c = 0; c < channels_; ++c) q1[c] = q0[c] + 0.5 * (t0[c] + t1[c]);
    }
  // The moments along each line (Line): over the piece [i, i + 1] of a line, G = Q_i + a(s) t_i +
  // b(s) t_(i+1), so its integral is Q_i + t_i / 3 + t_(i+1) / 6 and the integral of s G is
  // Q_i / 2 + 5 t_i / 24 + t_(i+1) / 8 (the moment of a = i + s adds i times the first).
  auto moments = [&](int q, int m1, int m2, bool along_rows) {
    const int lines = along_rows ? height_ : width_, cells = along_rows ? width_ : height_;
    for (int line = -1; line <= lines; ++line)
      for (int i = -1; i < cells; ++i) {
        auto entry = [&](int table, int k) {
          return along_rows ? at(table, k, line) : at(table, line, k);
        };
        const double *t0 = entry(kT, i), *t1 = entry(kT, i + 1), *g = entry(q, i);
        const double *a1 = entry(m1, i), *a2 = entry(m2, i);
        double *b1 = entry(m1, i + 1), *b2 = entry(m2, i + 1);
        for (int c = 0; c < channels_; ++c) {
          const double whole = g[c] + t0[c] / 3 + t1[c] / 6;
          b1[c] = a1[c] + whole;
          b2[c] = a2[c] + i * whole + 0.5 * g[c] + 5.0 / 24 * t0[c] + 0.125 * t1[c];
        }
      }
  };
  moments(kQT, kM1Row, kM2Row, true);
  moments(kTQ, kM1Column, kM2Column, false);
  data_ = tables_.data();
  size_ = tables_.size();
}

size_t SummedAreaTable::BlockBytes(int width, int height, int channels) {
  return sizeof(BlockHeader) + size_t{kTables} * (static_cast<size_t>(width) + 2) *
                                   (static_cast<size_t>(height) + 2) *
                                   static_cast<size_t>(channels) * sizeof(double);
}

std::vector<std::byte> SummedAreaTable::ToBytes() const {
  std::vector<std::byte> block(BlockBytes(width_, height_, channels_));
  WriteBlock(block.data());
  return block;
}

void SummedAreaTable::WriteBlock(std::byte* out) const {
  BlockHeader h{};
  std::memcpy(h.magic, kMagic, sizeof(kMagic));
  h.version = kSummedAreaTableVersion;
  h.width = width_, h.height = height_, h.channels = channels_;
  std::memcpy(out, &h, sizeof(h));
  std::memcpy(out + sizeof(h), data_, size_ * sizeof(double));
}

absl::StatusOr<std::unique_ptr<SummedAreaTable>> SummedAreaTable::View(
    std::span<const std::byte> block) {
  BlockHeader h;
  if (block.size() < sizeof(h))
    return absl::DataLossError("summed-area table block is shorter than its header");
  std::memcpy(&h, block.data(), sizeof(h));
  if (std::memcmp(h.magic, kMagic, sizeof(kMagic)) != 0 || h.version != kSummedAreaTableVersion)
    return absl::DataLossError("not a summed-area table block of this version");
  if (h.width < 1 || h.height < 1 || h.width > 65536 || h.height > 65536 ||
      (h.channels != 1 && h.channels != 3 && h.channels != 4))
    return absl::DataLossError(absl::StrCat("summed-area table block has a bad size ", h.width, "x",
                                            h.height, "x", h.channels));
  const size_t doubles = size_t{kTables} * (h.width + 2) * (h.height + 2) * h.channels;
  if (block.size() != sizeof(h) + doubles * sizeof(double))
    return absl::DataLossError(absl::StrCat("summed-area table block has ", block.size(),
                                            " bytes, not ", sizeof(h) + doubles * sizeof(double)));
  if (reinterpret_cast<uintptr_t>(block.data()) % alignof(double) != 0)
    return absl::InvalidArgumentError("summed-area table block is not 8-byte aligned");
  std::unique_ptr<SummedAreaTable> t(new SummedAreaTable());
  t->width_ = h.width, t->height_ = h.height, t->channels_ = h.channels;
  t->data_ = reinterpret_cast<const double*>(block.data() + sizeof(h));
  t->size_ = doubles;
  return t;
}

void SummedAreaTable::Corner(double x, double y, double* out) const {
  // x = c_i + s with c_i = i + 0.5, i in [-1, width - 1]; likewise y = c_j + r.
  const double xs = x - 0.5, ys = y - 0.5;
  const int i = std::clamp(static_cast<int>(std::floor(xs)), -1, width_ - 1);
  const int j = std::clamp(static_cast<int>(std::floor(ys)), -1, height_ - 1);
  const double s = xs - i, r = ys - j;
  const double as = s - 0.5 * s * s, bs = 0.5 * s * s;  // weights of t_i and t_(i+1)
  const double ar = r - 0.5 * r * r, br = 0.5 * r * r;
  const double *qq = At(kQQ, i, j), *qt0 = At(kQT, i, j), *qt1 = At(kQT, i, j + 1),
               *tq0 = At(kTQ, i, j), *tq1 = At(kTQ, i + 1, j), *t00 = At(kT, i, j),
               *t01 = At(kT, i, j + 1), *t10 = At(kT, i + 1, j), *t11 = At(kT, i + 1, j + 1);
  for (int c = 0; c < channels_; ++c)
    out[c] = qq[c] + ar * qt0[c] + br * qt1[c] + as * tq0[c] + bs * tq1[c] +
             as * (ar * t00[c] + br * t01[c]) + bs * (ar * t10[c] + br * t11[c]);
}

// The integral of texel column i's piecewise-linear samples over [y0, y1] (the one-axis form of
// Corner: TQ plus the partial trapezoid, at both ends).
void SummedAreaTable::AlongY(int i, double y0, double y1, double* out) const {
  double a[4], b[4];
  for (int e = 0; e < 2; ++e) {
    const double ys = (e == 0 ? y0 : y1) - 0.5;
    const int j = std::clamp(static_cast<int>(std::floor(ys)), -1, height_ - 1);
    const double r = ys - j, ar = r - 0.5 * r * r, br = 0.5 * r * r;
    const double *tq = At(kTQ, i, j), *t0 = At(kT, i, j), *t1 = At(kT, i, j + 1);
    double* g = e == 0 ? a : b;
    for (int c = 0; c < channels_; ++c) g[c] = tq[c] + ar * t0[c] + br * t1[c];
  }
  for (int c = 0; c < channels_; ++c) out[c] = b[c] - a[c];
}

// Texel row j's integral over [x0, x1] from QT.
void SummedAreaTable::AlongX(int j, double x0, double x1, double* out) const {
  double a[4], b[4];
  for (int e = 0; e < 2; ++e) {
    const double xs = (e == 0 ? x0 : x1) - 0.5;
    const int i = std::clamp(static_cast<int>(std::floor(xs)), -1, width_ - 1);
    const double s = xs - i, as = s - 0.5 * s * s, bs = 0.5 * s * s;
    const double *qt = At(kQT, i, j), *t0 = At(kT, i, j), *t1 = At(kT, i + 1, j);
    double* g = e == 0 ? a : b;
    for (int c = 0; c < channels_; ++c) g[c] = qt[c] + as * t0[c] + bs * t1[c];
  }
  for (int c = 0; c < channels_; ++c) out[c] = b[c] - a[c];
}

std::array<double, 4> SummedAreaTable::Integrate(double x0, double y0, double x1, double y1) const {
  std::array<double, 4> sum{};
  x0 = std::clamp(x0, 0.0, double(width_)), x1 = std::clamp(x1, x0, double(width_));
  y0 = std::clamp(y0, 0.0, double(height_)), y1 = std::clamp(y1, y0, double(height_));
  if (x1 <= x0 || y1 <= y0) return sum;
  // Within one cell between texel centres the texture is bilinear, and the integral of a bilinear
  // function over a rectangle is its area times the value at the rectangle's centre: four samples
  // instead of four corners of nine entries each (most of seed 003's fragments are this small).
  const double xs0 = x0 - 0.5, ys0 = y0 - 0.5;
  const double fi = std::floor(xs0), fj = std::floor(ys0);
  if (x1 - 0.5 <= fi + 1 && y1 - 0.5 <= fj + 1) {
    const int i = static_cast<int>(fi), j = static_cast<int>(fj);
    const double s = 0.5 * (x0 + x1) - 0.5 - fi, r = 0.5 * (y0 + y1) - 0.5 - fj;
    const double area = (x1 - x0) * (y1 - y0);
    const double w00 = (1 - s) * (1 - r) * area, w10 = s * (1 - r) * area, w01 = (1 - s) * r * area,
                 w11 = s * r * area;
    const double *t00 = At(kT, i, j), *t10 = At(kT, i + 1, j), *t01 = At(kT, i, j + 1),
                 *t11 = At(kT, i + 1, j + 1);
    for (int c = 0; c < channels_; ++c)
      sum[c] = w00 * t00[c] + w10 * t10[c] + w01 * t01[c] + w11 * t11[c];
    return sum;
  }
  // Within one cell column (row) the texture is linear across it: the integral is the width
  // times the integral along the column of the texture at the middle, from the one-axis prefix
  // sums of the two texel columns (rows) either side: 12 entries instead of 36 (seed 003's Gx
  // fragments are thin columns, its Gz fragments thin rows).
  if (x1 - 0.5 <= fi + 1) {
    const int i = static_cast<int>(fi);
    const double s = 0.5 * (x0 + x1) - 0.5 - fi;
    double g0[4], g1[4];
    AlongY(i, y0, y1, g0);
    AlongY(i + 1, y0, y1, g1);
    for (int c = 0; c < channels_; ++c) sum[c] = (x1 - x0) * ((1 - s) * g0[c] + s * g1[c]);
    return sum;
  }
  if (y1 - 0.5 <= fj + 1) {
    const int j = static_cast<int>(fj);
    const double r = 0.5 * (y0 + y1) - 0.5 - fj;
    double g0[4], g1[4];
    AlongX(j, x0, x1, g0);
    AlongX(j + 1, x0, x1, g1);
    for (int c = 0; c < channels_; ++c) sum[c] = (y1 - y0) * ((1 - r) * g0[c] + r * g1[c]);
    return sum;
  }
  double c11[4], c01[4], c10[4], c00[4];
  Corner(x1, y1, c11);
  Corner(x0, y1, c01);
  Corner(x1, y0, c10);
  Corner(x0, y0, c00);
  for (int c = 0; c < channels_; ++c) sum[c] = (c11[c] - c01[c]) - (c10[c] - c00[c]);
  return sum;
}

std::array<double, 4> SummedAreaTable::IntegratePeriodic(double x0, double y0, double x1,
                                                         double y1) const {
  std::array<double, 4> sum{};
  Piece px[3], py[3];
  const int nx = SplitPeriods(x0, x1, width_, px), ny = SplitPeriods(y0, y1, height_, py);
  for (int a = 0; a < nx; ++a)
    for (int b = 0; b < ny; ++b) {
      const auto part = Integrate(px[a].lo, py[b].lo, px[a].hi, py[b].hi);
      for (int c = 0; c < 4; ++c) sum[c] += px[a].count * py[b].count * part[c];
    }
  return sum;
}

}  // namespace aperture
