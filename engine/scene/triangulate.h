// Splits a simple planar polygon into triangles (ear clipping), or keeps it whole when convex.
#pragma once

#include <array>
#include <vector>

#include "absl/status/statusor.h"
#include "scene/vec.h"

namespace aperture {

// Signed area of a 2D polygon (positive when counter-clockwise).
double SignedArea(const std::vector<Vec2>& polygon);

bool IsConvex(const std::vector<Vec2>& polygon);

// Triangles as vertex index triples of a simple polygon given in 2D (either winding).
// Fails on self-intersecting input that leaves no ear.
absl::StatusOr<std::vector<std::array<int, 3>>> TriangulateEarClipping(
    const std::vector<Vec2>& polygon);

}  // namespace aperture
