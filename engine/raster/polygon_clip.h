// Clipping of convex polygons by half-planes (Sutherland-Hodgman), in 2D and 3D.
#pragma once

#include <vector>

#include "scene/vec.h"

namespace aperture {

// Keeps the part where a x + b y + c >= 0.
void ClipByHalfPlane(std::vector<Vec2>& polygon, double a, double b, double c,
                     std::vector<Vec2>& scratch);
// Keeps the part inside [x0, x1] x [y0, y1].
void ClipToRect(std::vector<Vec2>& polygon, double x0, double y0, double x1, double y1,
                std::vector<Vec2>& scratch);
// Keeps the part where dot(n, p) + d >= 0.
void ClipByPlane(std::vector<Vec3>& polygon, const Vec3& n, double d, std::vector<Vec3>& scratch);

}  // namespace aperture
