// The light benchmark's edge table (light_blink_bench.cc): one light 1 km away passing behind the
// slanted edge of a wall 100 m away as the camera slides sideways, frame by frame. Its energy per
// frame is set beside the analytic visible share of its footprint (the octagon Aperture draws,
// clipped by the wall's projected quad: support/footprint_clip.h): Aperture must dim
// monotonically, each step the share's own change; llvmpipe's points, depth tested against the
// wall as an image generator draws them, pop.
#pragma once

#include "absl/status/status.h"
#include "light_point_peer.h"
#include "raster/aa_filter.h"

namespace aperture {

struct EdgeRunOptions {
  int width = 1280, height = 720;
  AntiAliasing aa = AntiAliasing::kBox2;
  int frames = 120;
  double step_px = 0.025;  // how far the edge moves across the light each frame, pixels
  double peer_min_size = 1.5;
  // Aperture's largest step may exceed the share's change by this much (of the light's energy)
  // before the run reports it as a failure: the float images' rounding.
  double tolerance = 1e-5;
  int print_every = 10;  // a row of the per-frame table every this many frames (0: none)
};

// Prints the table and the summary; an error when a renderer fails or the light leaves the frame.
// `passed` (may be null): whether Aperture was monotone with every step within the tolerance.
absl::Status RunEdge(LightPointPeer& peer, const EdgeRunOptions& options, bool* passed);

}  // namespace aperture
