// Synthetic scenes for benchmarks: a field of random triangles (to compare exact edges with a
// software rasterizer's) seen by a camera at the origin looking along -z.
#pragma once

#include <cstdint>

#include "aperture/v1/scene.pb.h"

namespace aperture {

// `count` triangles scattered over the view at depths 10..100, each about `screen_size` pixels
// across on a 1920 x 1080 image with a 60 degree vertical field of view; lit, untextured.
v1::Scene MakeTriangleFieldScene(int count, double screen_size = 40, uint32_t seed = 1);

// The tris-N scene, the peer benchmark's (scripts/bench-peers.sh): `count` triangles with
// centres uniform over a `width` x `height` frame (60 degree vertical field of view, camera at the
// origin looking along -z), vertices at most `radius_px` pixels from their centre, flat unlit
// colours from a palette of 64; each later triangle lies in front of every earlier one (depths
// from 100 down to 10, facing the camera), so the frame is the triangles painted in order.
v1::Scene MakeTrisScene(int count, double radius_px = 12, int width = 1920, int height = 1080,
                        uint32_t seed = 19);

// The slivers-N scene: `count` slivers (2 units long, 0.02 wide, unlit, two colours)
// spread evenly over the view of the camera at the origin looking along -z (a golden-ratio
// sequence of centres over 12 x 12 units, turning 7.3 half-turns in all), on 13 planes facing the
// camera at z = -10 - 0.001 (i mod 13): every window is mixed and overlapping slivers are often
// coplanar. The service tests' slow frame; its cost grows linearly with N.
v1::Scene MakeSliversScene(int count);

// The skewed scene: a dense city block (a 30 x 30 grid of buildings, 4,500 polygons) in
// the lower-left corner of the view of a camera at the origin looking along -z; sky elsewhere.
v1::Scene MakeSkewedCityScene(uint32_t seed = 2);

}  // namespace aperture
