// The canonical quality benchmark of DESIGN.md, computed directly per pixel: the ground plane
// y = 0 with u = x / 4, v = z / 4 (texture repeated), seen from (0, 1, 0) looking along -z (or
// turned by a yaw) and pitched down by theta, vertical field of view 60 degrees. Footprints are
// evaluated analytically (seed 000, eq. 1-2 for this plane) and the reference integrates the
// bilinear texture over each pixel's a x a screen square by stratified supersampling.
#pragma once

#include <cmath>
#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <vector>

#include "base/image.h"
#include "scene/scene.h"
#include "texture/texture_sampler.h"

namespace aperture {

struct GrazingPlaneView {
  int width = 1024, height = 768;
  double pitch_deg = 5;  // downwards
  double fov_deg = 60;   // vertical
  double aperture = 2;   // a: 2 = the paper's 2 x 2 pixel square, 1 = the pixel
  // The camera turned about the vertical by this much (the texture's axes turned the other way
  // under it): 0 looks along the texture's v axis (the filter benchmark turns it from 0 to 90
  // degrees).
  double yaw_deg = 0;
  // The texture coordinates (repeats) of the ground under the camera: moving the camera over the
  // plane (aperture-bench flicker's fly-over) moves them.
  double origin_u = 0, origin_v = 0;
};

// Texture coordinates (repeats, not wrapped) of the ground under image point (px, py) (pixel
// centres at +0.5); false above the horizon.
bool GroundPoint(const GrazingPlaneView& view, double px, double py, double* u, double* v);
// The footprint of pixel (i, j): (u, v) wrapped to [0, 1), derivatives times the aperture.
bool GroundFootprint(const GrazingPlaneView& view, int i, int j, TextureFootprint* f);
// The first row whose whole 2 x 2 aperture lies below the horizon (the measured rows).
int FirstMeasuredRow(const GrazingPlaneView& view);

// The plane as a scene for the ray tracer (seed 003): a 40 km square ground polygon at y = 0, u =
// x / 4, v = z / 4 (repeats), unlit white under `texture`, black sky; seen from (0, 1, 0) with the
// view's pitch it is the view above (at yaw 0).
Scene GrazingPlaneScene(std::shared_ptr<const SceneTexture> texture);

// Every pixel through `sampler` (sky = 0), in parallel with oneTBB.
Image RenderGroundImage(const GrazingPlaneView& view, const TextureSampler& sampler);
// Nanoseconds per sample of `sampler`, single-threaded, over the measured rows' footprints
// (every `rows_step`-th row); the fastest of three passes.
double NanosecondsPerSample(const GrazingPlaneView& view, const TextureSampler& sampler,
                            int rows_step = 1);
// The reference: per pixel, the average of the bilinear texture over the a x a square by
// stratified jittered samples, `density` strata per texel of extent per side
// (min_per_side..max_per_side). Only rows [first_row, end_row) (end_row < 0: to the bottom); the
// others are black.
Image RenderGroundReference(const GrazingPlaneView& view, const Image& texture, double density,
                            int max_per_side, int min_per_side = 2, int first_row = 0,
                            int end_row = -1);
// Moves the camera `world_units` forward along its heading (the turned view axis, on the ground):
// the view's texture origin moves with it (aperture-bench flicker's fly-over).
void MoveForward(GrazingPlaneView* view, double world_units);
// The view with the camera moved over the plane to position k (k = 0: the view itself). For
// textures of 1024 texels the first 2^m positions meet the checkerboard's 128-texel cells at
// 2^m evenly spread phases along U and along V alike, lie in different cells of the repeat, and
// spread their phases within a texel (the .cc says how). Looking along a texture axis, every
// pixel row meets the texels and the checkerboard's edges at one phase, so one position scores
// one phase: aperture-bench filter --positions pools several.
GrazingPlaneView ViewAtPosition(const GrazingPlaneView& view, int k);
// The spread of one view's PSNR across yaws (a filter should score alike from every direction):
// the highest minus the lowest, and the yaw of the lowest (the first where two tie). Empty or
// unequal spans: spread 0, yaw NaN.
struct YawSpread {
  double spread = 0;
  double lowest_yaw = NAN;
};
YawSpread SpreadAcrossYaws(std::span<const double> yaws, std::span<const double> psnrs);
// PSNR (peak 1) over RGB of rows [first_row, height).
double Psnr(const Image& a, const Image& b, int first_row);
// The PSNR of the mean squared error of several measurements of equal pixel counts, given
// their PSNRs (infinite for no error).
double PooledPsnr(std::span<const double> psnrs);
// Mean over rows [first_row, height) and RGB of |a - a_prev|, or with a reference sequence
// (r, r_prev not null) of |(a - a_prev) - (r - r_prev)|: the change between two frames a filter
// makes beyond the reference's (aperture-bench flicker's excess flicker).
double MeanAbsoluteChange(const Image& a, const Image& a_prev, const Image* r, const Image* r_prev,
                          int first_row);
// PSNR of each row (RGB, peak 1); rows before `first_row` are NaN.
std::vector<double> PsnrByRow(const Image& a, const Image& b, int first_row);
// The longer of pixel (i, j)'s two one-pixel steps in texels of a texture_size texture (0 above
// the horizon).
double FootprintLength(const GrazingPlaneView& view, int i, int j, int texture_size);
// The angle in degrees, 0..45, between pixel (i, j)'s footprint's long axis (the principal axis
// of the second moments of its two steps) and the nearest texture axis (0 above the horizon).
// The table's copies have sides parallel to an axis, so a filter of seed 000 may depend on it.
double FootprintAngleFromAxis(const GrazingPlaneView& view, int i, int j);
// PSNR of the same rows by band of a pixel measure: band k holds the pixels whose measure(i, j)
// lies in [edges[k-1], edges[k]) (the first from -infinity, the last without end); `pixels`:
// how many each band holds.
std::vector<double> PsnrByBand(const Image& a, const Image& b, int first_row,
                               const std::function<double(int, int)>& measure,
                               const std::vector<double>& edges,
                               std::vector<uint64_t>* pixels = nullptr);
// PsnrByBand of FootprintLength.
std::vector<double> PsnrByFootprintBand(const Image& a, const Image& b,
                                        const GrazingPlaneView& view, int texture_size,
                                        int first_row, const std::vector<double>& edges,
                                        std::vector<uint64_t>* pixels = nullptr);

}  // namespace aperture
