// Independent references for image tests: dense point sampling of the projected polygons, with
// no use of the analytic coverage code.
#pragma once

#include <functional>

#include "base/image.h"
#include "raster/aa_filter.h"
#include "raster/projection.h"

namespace aperture::testing {

// The world point on the plane z = -depth that a camera at the origin looking along -z (60 degree
// vertical field of view) sees at screen point (px, py) of a width x height frame: polygons
// placed in pixels.
Camera OriginCamera();
Vec3 PointAtPixel(int width, int height, double px, double py, double depth);

// Colour of each polygon (flat), by frame polygon index.
using FlatColour = std::function<Rgba(int polygon)>;

// Pixel (px, py) filtered with `aa` by n x n stratified samples over its aperture; at each sample
// the nearest polygon containing it (largest 1/depth) is seen, else `sky`.
Rgba DenseReferencePixel(const FrameGeometry& geo, const FlatColour& colour, Rgba sky,
                         AntiAliasing aa, int px, int py, int n);

// The same with transparency: at each sample every polygon containing it is composited front to
// back with its colour's alpha (a flat alpha per polygon, so the result is the exact filtered
// composite), over `sky` (whose alpha is the result's where nothing covers). Returns the
// filtered colour and alpha (1 - what reaches a transparent sky).
Rgba DenseCompositedPixel(const FrameGeometry& geo, const FlatColour& colour, Rgba sky,
                          AntiAliasing aa, int px, int py, int n);

}  // namespace aperture::testing
