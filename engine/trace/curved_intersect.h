// Exact ray intersections with seed 003's curved primitives (spheres, finite cylinders with or
// without caps), in double precision. Embree's user geometry calls these for the BVH; the trace
// renderer calls them again from the camera's exact position for the hit point it maps.
#pragma once

#include <optional>

#include "scene/scene.h"

namespace aperture {

// Which sheet of the surface a ray met. Corners of a pixel agree only on the same primitive and
// part: the outside and the inside of an open cylinder map to the same texture but are different
// surfaces on screen.
enum class CurvedPart { kOutside = 0, kInside = 1, kBottomCap = 2, kTopCap = 3 };

struct CurvedHit {
  double t = 0;  // along the ray: point = origin + t dir
  CurvedPart part = CurvedPart::kOutside;
  Vec3 point;   // world space
  Vec3 normal;  // unit, geometric (outward of the solid; the cap's outward side)
};

// The nearest hit with t in (t_near, t_far]; nullopt when there is none. `dir` need not be unit.
std::optional<CurvedHit> IntersectCurved(const CurvedPrimitive& c, const Vec3& origin,
                                         const Vec3& dir, double t_near, double t_far);

// The primitive's bounding box (world space).
void CurvedBounds(const CurvedPrimitive& c, Vec3* lo, Vec3* hi);

}  // namespace aperture
