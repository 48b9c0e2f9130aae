// Summed-area tables (seed 003's ref. 8, Crow 1984) for raster textures: the exact integral of the
// continuous texture over an axis-aligned rectangle with fractional edges, in O(1).
//
// The continuous texture is the one DESIGN.md's grazing-plane reference samples: the bilinear
// reconstruction of the texels, texel (i, j) centred at (i + 0.5, j + 0.5) in texel units, repeated
// periodically. Along one axis it is piecewise linear between texel centres c_i = i + 0.5, so its
// integral G(x) from c_-1 is piecewise quadratic: for x = c_i + s, 0 <= s < 1,
//   G(x) = Q_i + a(s) t_i + b(s) t_(i+1),  a(s) = s - s^2 / 2,  b(s) = s^2 / 2,
// with Q_i the trapezoid sums of the samples up to c_i. In two dimensions the integral from the
// corner is the tensor product of two such functionals, which needs four tables: the samples T,
// the trapezoid prefix sums along x of every row (QT), along y of every column (TQ) and both (QQ).
// Every table is accumulated in double, so a 4096 x 4096 texture keeps about 1e-9 absolute
// precision (the sums reach 1.7e7; double carries 16 digits).
//
// Four more tables serve integrals over polygons by Green's theorem (trace/polygon_integral.h):
// along every row, the prefix integral M1 of G and the prefix moment M2 of a G (a the coordinate
// along the row), and the same along every column. With them an edge's integral costs one step per
// row (or column) it crosses, whatever its length along the other axis.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "base/image.h"

namespace aperture {

// The version of the block (ToBytes / View) and of the store key: a change to the block's layout
// raises it, so that no process maps a block of another layout.
inline constexpr uint32_t kSummedAreaTableVersion = 3;

class SummedAreaTable {
 public:
  // `channels` = 1 (red only), 3 (RGB) or 4 (RGBA) of `image` are tabulated.
  explicit SummedAreaTable(const Image& image, int channels = 4);
  SummedAreaTable(const SummedAreaTable&) = delete;
  SummedAreaTable& operator=(const SummedAreaTable&) = delete;

  // The tables as one block (a 32-byte header: magic, version, width, height, channels; then the
  // doubles), for the shared store: every process maps it and uses it in place.
  std::vector<std::byte> ToBytes() const;
  // The same block written to `out`, which holds BlockBytes(width(), height(), channels()) bytes.
  void WriteBlock(std::byte* out) const;
  // A table over such a block (8-byte aligned), which must outlive it; checks the header and size.
  static absl::StatusOr<std::unique_ptr<SummedAreaTable>> View(std::span<const std::byte> block);

  // The size of ToBytes' block for a `width` x `height` texture of `channels`, known before the
  // table is built (a store with a budget refuses a block that cannot fit before building it).
  static size_t BlockBytes(int width, int height, int channels);

  int width() const { return width_; }
  int height() const { return height_; }
  int channels() const { return channels_; }
  size_t bytes() const { return size_ * sizeof(double); }

  // The integral of the continuous texture over [x0, x1] x [y0, y1] in texel units, within one
  // period: 0 <= x0 <= x1 <= width, 0 <= y0 <= y1 <= height (clamped to it). Channels past
  // channels() are 0.
  std::array<double, 4> Integrate(double x0, double y0, double x1, double y1) const;

  // The same over any rectangle of the periodic plane (split at the period borders).
  std::array<double, 4> IntegratePeriodic(double x0, double y0, double x1, double y1) const;

  // The integral over [-0.5, x] x [-0.5, y] (from the centre of texel (-1, -1)), per channel;
  // x in [-0.5, width + 0.5], likewise y.
  void Corner(double x, double y, double* out) const;

  // One texel row (`along_rows`) or column, `line` in [-1, height] (resp. width), as a function
  // of the coordinate a along it, measured from texel centres (a = x - 0.5 along a row): G(a) its
  // integral from a = -1, M1(a) the integral of G from -1, M2(a) the integral of a G(a) from -1.
  // `cell` is the piece of the line a lies in, a in [cell, cell + 1], cell in [-1, size - 1].
  struct LineIntegrals {
    double g[4], m1[4], m2[4];
  };
  void Line(bool along_rows, int line, int cell, double a, bool moments, LineIntegrals* out) const {
    const int i = along_rows ? cell : line, j = along_rows ? line : cell;
    const LinePiece p = PieceOf(along_rows, i, j);
    const double *t0 = p.t0, *t1 = p.t1, *q = p.q;
    const double s = a - cell, s2 = s * s;
    const double as = s - 0.5 * s2, bs = 0.5 * s2;  // the weights of G (as in Corner)
    for (int c = 0; c < channels_; ++c) out->g[c] = q[c] + as * t0[c] + bs * t1[c];
    if (!moments) return;
    // Their integrals from the piece's start: s^2 / 2 - s^3 / 6 and s^3 / 6; and of s times them.
    const double s3 = s2 * s, s4 = s3 * s;
    const double A = 0.5 * s2 - s3 / 6, B = s3 / 6, A2 = s3 / 3 - 0.125 * s4, B2 = 0.125 * s4;
    const double *m1 = At(along_rows ? kM1Row : kM1Column, i, j),
                 *m2 = At(along_rows ? kM2Row : kM2Column, i, j);
    for (int c = 0; c < channels_; ++c) {
      const double part = s * q[c] + A * t0[c] + B * t1[c];
      out->m1[c] = m1[c] + part;
      out->m2[c] = m2[c] + cell * part + 0.5 * s2 * q[c] + A2 * t0[c] + B2 * t1[c];
    }
  }
  // G alone at two points a0, a1 of one piece (`cell`), in g0 and g1. Inline: the exact
  // integral's inner loop (trace/polygon_integral) calls it twice per step.
  void LineAt2(bool along_rows, int line, int cell, double a0, double a1, double* g0,
               double* g1) const {
    const LinePiece p = PieceOf(along_rows, along_rows ? cell : line, along_rows ? line : cell);
    const double *t0 = p.t0, *t1 = p.t1, *q = p.q;
    const double s0 = a0 - cell, s1 = a1 - cell;
    const double as0 = s0 - 0.5 * s0 * s0, bs0 = 0.5 * s0 * s0;
    const double as1 = s1 - 0.5 * s1 * s1, bs1 = 0.5 * s1 * s1;
    auto channels = [&](int n) {
      for (int c = 0; c < n; ++c) {
        g0[c] = q[c] + as0 * t0[c] + bs0 * t1[c];
        g1[c] = q[c] + as1 * t0[c] + bs1 * t1[c];
      }
    };
    if (channels_ == 3)
      channels(3);  // RGB, the common table: a loop of known length
    else
      channels(channels_);
  }

 private:
  // One-axis integrals of texel column i over [y0, y1], of texel row j over [x0, x1].
  void AlongY(int i, double y0, double y1, double* out) const;
  void AlongX(int j, double x0, double x1, double* out) const;
  const double* At(int table, int i, int j) const {
    return &data_[((static_cast<size_t>(j + 1) * (width_ + 2) + (i + 1)) * kTables + table) *
                  channels_];
  }
  // The entries one piece of a line reads: its samples at both ends and the prefix sum (QT along
  // rows, TQ along columns) at its start, entry (i, j).
  struct LinePiece {
    const double *t0, *t1, *q;
  };
  LinePiece PieceOf(bool along_rows, int i, int j) const {
    return {At(kT, i, j), along_rows ? At(kT, i + 1, j) : At(kT, i, j + 1),
            At(along_rows ? kQT : kTQ, i, j)};
  }
  SummedAreaTable() = default;
  // The tables, interleaved per texel in this order.
  enum Table { kT, kQT, kTQ, kQQ, kM1Row, kM2Row, kM1Column, kM2Column, kTables };

  int width_ = 0, height_ = 0, channels_ = 0;
  // Eight tables T, QT, TQ, QQ, M1 and M2 along rows, M1 and M2 along columns, each (width + 2) x
  // (height + 2) entries for texel indices -1 .. width (resp. height), the borders wrapped;
  // interleaved per texel (the tables, each with its channels), so that one corner's nine reads
  // touch few cache lines.
  std::vector<double> tables_;    // owned (built here), or empty for a view
  const double* data_ = nullptr;  // tables_.data() or the viewed block's
  size_t size_ = 0;
};

}  // namespace aperture
