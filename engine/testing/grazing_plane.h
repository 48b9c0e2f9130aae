// The canonical quality benchmark of DESIGN.md, computed directly per pixel: the ground plane
// y = 0 with u = x / 4, v = z / 4 (texture repeated), seen from (0, 1, 0) looking along -z and
// pitched down by theta, vertical field of view 60 degrees. Footprints are evaluated
// analytically (seed 000, eq. 1-2 for this plane) and the reference integrates the bilinear
// texture over each pixel's a x a screen square by stratified supersampling.
#pragma once

#include <functional>

#include "base/image.h"
#include "texture/texture_sampler.h"

namespace aperture {

struct GrazingPlaneView {
  int width = 1024, height = 768;
  double pitch_deg = 5;  // downwards
  double fov_deg = 60;   // vertical
  double aperture = 2;   // a: 2 = the paper's 2 x 2 pixel square, 1 = the pixel
};

// Texture coordinates (repeats, not wrapped) of the ground under image point (px, py) (pixel
// centres at +0.5); false above the horizon.
bool GroundPoint(const GrazingPlaneView& view, double px, double py, double* u, double* v);
// The footprint of pixel (i, j): (u, v) wrapped to [0, 1), derivatives times the aperture.
bool GroundFootprint(const GrazingPlaneView& view, int i, int j, TextureFootprint* f);
// The first row whose whole 2 x 2 aperture lies below the horizon (the measured rows).
int FirstMeasuredRow(const GrazingPlaneView& view);

// Every pixel through `sampler` (sky = 0), in parallel with oneTBB.
Image RenderGroundImage(const GrazingPlaneView& view, const TextureSampler& sampler);
// Nanoseconds per sample of `sampler`, single-threaded, over the measured rows' footprints
// (every `rows_step`-th row); the fastest of three passes.
double NanosecondsPerSample(const GrazingPlaneView& view, const TextureSampler& sampler,
                            int rows_step = 1);
// The reference: per pixel, the average of the bilinear texture over the a x a square by
// stratified jittered samples, `density` strata per texel of extent per side (2..max_per_side).
Image RenderGroundReference(const GrazingPlaneView& view, const Image& texture, double density,
                            int max_per_side);
// PSNR (peak 1) over RGB of rows [first_row, height).
double Psnr(const Image& a, const Image& b, int first_row);

}  // namespace aperture
