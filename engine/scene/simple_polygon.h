// Is a polygon simple? No two edges that are not neighbours along the boundary meet, and two
// neighbours meet only at their shared vertex (docs/SCENE.md refuses self-intersecting polygons:
// their inside is ambiguous). A Shamos-Hoey sweep: O(n log n) for n vertices, so a 200,000-vertex
// ground polygon is checked in milliseconds.
#pragma once

#include <vector>

#include "absl/status/status.h"
#include "scene/vec.h"

namespace aperture {

// OK for a simple polygon; otherwise InvalidArgument naming two edges that meet ("edges 3 and 7
// cross"; edge i runs from vertex i to vertex i + 1). Consecutive repeated vertices are allowed
// (they make an edge of length 0, which is skipped).
absl::Status CheckSimplePolygon(const std::vector<Vec2>& polygon);

}  // namespace aperture
