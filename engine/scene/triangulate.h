// Splits a simple planar polygon into triangles in O(n log n) (monotone pieces), or keeps it whole
// when convex.
#pragma once

#include <array>
#include <span>
#include <vector>

#include "absl/status/statusor.h"
#include "scene/vec.h"

namespace aperture {

// Signed area of a 2D polygon (positive when counter-clockwise).
double SignedArea(std::span<const Vec2> polygon);

// Convex and simple: every turn the same way (or straight on) and one turn round in all.
bool IsConvex(std::span<const Vec2> polygon);

// Triangles as counter-clockwise vertex index triples of a simple polygon given in 2D (either
// winding): n - 2 of them, O(n log n) time. Fails with InvalidArgument on input the sweep finds
// self-intersecting (not every self-intersection is found).
absl::StatusOr<std::vector<std::array<int, 3>>> TriangulatePolygon(
    const std::vector<Vec2>& polygon);

}  // namespace aperture
