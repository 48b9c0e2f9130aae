// Seed 003: the pixel's projection abcd on the texture plane covered by axis-parallel rectangles
// ("fragments"), and the fragments cut into child fragments per unit texture.
//
// Texture-plane coordinates (x, z) are in texture repeats: the unit texture is [0, 1)^2, repeated
// periodically (x runs along the texture's columns, u; z along its rows, v). The grid of level k
// has lines x = m 2^-k and z = m 2^-k (seed 003: l^(k) = 2^-k, the classification squares of its
// ref. 10).
#pragma once

#include <array>
#include <vector>

namespace aperture {

struct TexPoint {
  double x = 0, z = 0;
};

// [x0, x1] x [z0, z1].
struct TexRect {
  double x0 = 0, z0 = 0, x1 = 0, z1 = 0;
  double Area() const { return (x1 - x0) * (z1 - z0); }
};

// How the grid level is chosen.
enum class FragmentLevelRule {
  // Per axis, from a bound that holds: a column's rectangle exceeds the quad's part in it by at
  // most l times the z-variation of the quad's boundary in that column, so the columns (Gx) of a
  // convex quad exceed it by at most l Z (Z its extent along z) and l <= delta S / Z keeps the
  // relative error within delta; likewise l <= delta S / X for the rows (Gz). The set is checked
  // and refined one level while it is not. A long, thin quad along an axis gets about 1 / delta
  // fragments however long it is, where eq. 9 (which bounds by P / 2S) gives one per l of its
  // length (a deviation from seed 003: on the grazing plane at 20 degrees, 44 fragments a pixel
  // instead of 98 for 0.28 dB; build/tests/raytrace_quality_bench).
  kPerAxisBound,
  kEquationNine,  // seed 003, eq. 9: one level for both axes from delta S / P
};

struct FragmentOptions {
  double delta = 0.1;    // allowed relative area error of the cover (seed 003, eq. 5)
  int max_level = 30;    // the finest grid, 2^-30 repeats
  int max_cells = 1024;  // grid columns (rows) per quad at most: coarser levels beyond that
  FragmentLevelRule rule = FragmentLevelRule::kPerAxisBound;
  // A raster texture's quad is integrated exactly (trace/polygon_integral.h) when that takes at
  // most this many steps (row or column bands summed over its edges), else by the fragments
  // above; 0 integrates every quad by fragments, as seed 003 does.
  // 256: the fastest of 64 .. 1024 on the demo and the grazing plane (aperture-render --mode
  // raytrace --exact_steps S).
  int exact_steps = 256;
};

struct FragmentSet {
  std::vector<TexRect> fragments;  // disjoint, covering the quad
  double area = 0;                 // S_fragments: their total area
  double quad_area = 0;            // S_quad (shoelace)
  double quad_perimeter = 0;       // P_quad
  int level = 0;                   // k of the kept set
  bool columns = true;             // Gx (grouped by grid column) kept, else Gz (rows)
};

// seed 003, eq. 9: k = ceil(-log2(delta S / P) - 1), the level whose squares of side 2^-k keep
// the relative area error of the cover near delta (eq. 8: delta ~ 2^-k P / (2 S)).
int FragmentLevel(double delta, double quad_area, double quad_perimeter);

// Covers the quad a, b, c, d (in order around it, either orientation) with fragments, as seed 003
// lays out: level k (by `options.rule`, clamped by `options`), the edges' crossings with the lines
// x = const (list Lx, with a, b, c, d) and z = const (list Lz), each list sorted, grouped by grid
// column (row), each group's bounding rectangle a fragment: sets Gx and Gz; the one with the
// smaller total area is kept. A point on a grid line belongs to both cells it separates, so each
// group's rectangle bounds the quad's part in its column and the set covers the quad. With eq. 9
// the set of smaller area is kept; with the per-axis rule (each set at its own level) the one of
// fewer fragments, then smaller area. A degenerate quad (zero area) gets its bounding box as one
// fragment.
void BuildFragments(const std::array<TexPoint, 4>& quad, const FragmentOptions& options,
                    FragmentSet* out);

// A fragment cut at the unit-texture borders: child fragments in normalised coordinates within
// [0, 1]^2 (seed 003: P_N in [0, 1)^2), appended to `out`.
void ChildFragments(const TexRect& fragment, std::vector<TexRect>* out);

}  // namespace aperture
