// Texture footprints of pixel centres on a polygon (seed 000, eq. 1-2): perspective-correct
// texture coordinates and their screen derivatives. One function per sample, which the shader
// uses everywhere, and kernels for a run of pixel centres along a row (the interior of a
// polygon): the portable one calls the per-sample functions; AVX2 (chosen at run time when the
// processor has it) does four pixels at a time with the same operations in the same order and no
// fused multiply-add, so that both give the same bits (tests/render/footprint_kernels_test.cc).
#pragma once

#include <algorithm>
#include <cmath>

#include "raster/screen_polygon.h"
#include "texture/footprint_batch.h"

namespace aperture {

// 1 / depth at (x, y), kept at least `min_inv_depth` (the polygon's farthest vertex), so that
// extrapolation beyond the polygon's edges stays sane.
inline double InvDepthAt(const ScreenPolygon& p, double min_inv_depth, double x, double y) {
  return std::max(p.inv_depth.At(x, y), min_inv_depth);
}

// The footprint at (x, y) given w = InvDepthAt(...); derivatives scaled by the aperture a.
inline TextureFootprint FootprintAt(const ScreenPolygon& p, double aperture, double w, double x,
                                    double y) {
  // seed 000, eq. 1: U = (A_u x + B_u y + C_u) / (A_z x + B_z y + C_z).
  const double inv_w = 1.0 / w;
  const double u = p.u_num.At(x, y) * inv_w, v = p.v_num.At(x, y) * inv_w;
  // seed 000, eq. 2: dU/dx = (A_u - A_z U) / z0, scaled by the aperture a.
  const double s = aperture * inv_w;
  TextureFootprint f;
  f.u = u - std::floor(u);
  f.v = v - std::floor(v);
  f.dudx = static_cast<float>((p.u_num.a - p.inv_depth.a * u) * s);
  f.dvdx = static_cast<float>((p.v_num.a - p.inv_depth.a * v) * s);
  f.dudy = static_cast<float>((p.u_num.b - p.inv_depth.b * u) * s);
  f.dvdy = static_cast<float>((p.v_num.b - p.inv_depth.b * v) * s);
  return f;
}

// The pixel centres x0 + (first + i), y for i < count (count <= FootprintBatch::kMax): their
// footprints into out (out.count = count) and their InvDepthAt into inv_depth[i].
struct RowRun {
  double x0, y;
  int first, count;
};
using RowFootprintsFn = void (*)(const ScreenPolygon& p, double min_inv_depth, double aperture,
                                 const RowRun& run, FootprintBatch& out, double* inv_depth);

void RowFootprintsPortable(const ScreenPolygon& p, double min_inv_depth, double aperture,
                           const RowRun& run, FootprintBatch& out, double* inv_depth);
// Null when the build or the processor lacks AVX2.
RowFootprintsFn RowFootprintsAvx2();
// The fastest this processor runs, and its name.
RowFootprintsFn BestRowFootprints();
const char* BestRowFootprintsName();

}  // namespace aperture
