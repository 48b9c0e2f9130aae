// Independent references for image tests: dense point sampling of the projected polygons, with
// no use of the analytic coverage code.
#pragma once

#include <functional>

#include "raster/aa_filter.h"
#include "raster/projection.h"
#include "texture/image.h"

namespace aperture::testing {

// Colour of each polygon (flat), by frame polygon index.
using FlatColour = std::function<Rgba(int polygon)>;

// Pixel (px, py) filtered with `aa` by n x n stratified samples over its aperture; at each sample
// the nearest polygon containing it (largest 1/depth) is seen, else `sky`.
Rgba DenseReferencePixel(const FrameGeometry& geo, const FlatColour& colour, Rgba sky,
                         AntiAliasing aa, int px, int py, int n);

}  // namespace aperture::testing
