// The exact integral of a raster texture's bilinear reconstruction over a pixel's projection, by
// Green's theorem over the projection's edges against the summed-area table's line integrals: a
// step beyond seed 003's fragments (the quad's edges integrated against the table's column
// sums), exact where the fragments are only within delta of the area, and at a
// cost that grows with the rows or columns an edge crosses, not with the area it bounds.
//
// With F(x, y) the integral of the texture along its row from x = -0.5 and G(x, y) the same along
// its column, the integral over a polygon P is the loop integral of F dy (or of -G dx) around it,
// and dC = G dx + F dy for the table's corner integral C. Per edge the cheaper form is taken: F dy
// costs one step per row band the edge crosses, G dx one per column band; an edge taken as -G dx
// adds C(end) - C(start), so only the corners where the form changes are looked up. Within a band
// the integrand is the line integral of the two texel lines bounding it, weighted linearly across
// the band: a cubic in the edge's parameter within one cell (two Gauss-Legendre points are exact),
// and over many cells the difference of the lines' prefix moments M1 and M2.
#pragma once

#include <array>

#include "texture/summed_area_table.h"
#include "trace/pixel_fragments.h"

namespace aperture {

// The mean of the texture over the simple quad (texture repeats, any position, either
// orientation), exact to rounding, in `mean`. The work is the `steps`: row or column bands, and
// periods within them, over all edges, one per edge at least. False, and `mean` untouched, when
// the quad is not simple (a bow tie), has no area, spans more than 4,096 unit textures, takes more
// than `max_steps` steps, or the table is over 4,096 texels on a side (for precision): the caller
// then uses seed 003's fragments.
bool PolygonMean(const std::array<TexPoint, 4>& quad, const SummedAreaTable& table, int max_steps,
                 std::array<double, 4>* mean, int* steps = nullptr);

// The integral over a simple polygon of `n` (at most 16) vertices in texel units, anywhere on the
// repeating texture (near the origin for precision), signed: positive when the vertices run
// counterclockwise in (x, y).
std::array<double, 4> PolygonIntegral(const SummedAreaTable& table, const TexPoint* vertices,
                                      int n);

}  // namespace aperture
