// Seed 003, eq. 1-2: the texture mapping F = F2(F1(P)) of a primitive. F1 takes a point of the
// primitive (in the primitive's own frame) to the texture plane X'_T Z'_T: linear (planar faces),
// cylindrical or spherical; F2 is an affine transform of that plane (scale, rotation, shift).
// Spheres and cylinders (scene.curved) take the spherical and cylindrical F1 on their surface and
// a disc's linear F1 on a cylinder's caps.
#pragma once

#include <array>

#include "scene/scene.h"
#include "scene/vec.h"
#include "trace/pixel_fragments.h"

namespace aperture {

// F2: (x, z) -> (a x + b z + e, c x + d z + f).
struct Affine2 {
  double a = 1, b = 0, c = 0, d = 1, e = 0, f = 0;

  // Scale (sx, sz) first, then rotation by `angle_deg` (counter-clockwise), then the shift.
  static Affine2 ScaleRotateShift(double sx, double sz, double angle_deg, double shift_x,
                                  double shift_z);
  TexPoint Apply(const TexPoint& p) const { return {a * p.x + b * p.z + e, c * p.x + d * p.z + f}; }
};

enum class MappingKind { kLinear, kCylindrical, kSpherical, kDisc };

struct PrimitiveMapping {
  MappingKind kind = MappingKind::kLinear;
  // The primitive's frame: P_ij = axes^T (P - origin) (columns of `axes`: the frame's x, y, z in
  // world space; y is the cylinder's axis and the sphere's pole).
  Vec3 origin;
  Mat3 axes;
  // kLinear: x' = dot(su, P_ij), z' = dot(sv, P_ij).
  Vec3 su{1, 0, 0}, sv{0, 0, 1};
  // kCylindrical: z' = y / height (the cylinder from y = 0 to height).
  double height = 1;
  // kDisc (a cylinder's cap): x' = (x / radius + 1) / 2, z' = (z / radius + 1) / 2, one repeat
  // across the diameter.
  double radius = 1;
  Affine2 f2;
};

// F1: x' = atan2(x, z) / 2 pi in [0, 1) around the axis (cylindrical, spherical); z' = y /
// height (cylindrical) or the polar angle from +y over pi, in [0, 1] (spherical).
TexPoint F1(const PrimitiveMapping& mapping, const Vec3& world_point);

// F = F2(F1(P)) of the four corner hits of a pixel (seed 003's A, B, C, D -> a, b, c, d). Around
// the seam of the angle (x' = 0 = 1) the corners are unwrapped next to the first one, so that the
// quad is the pixel's projection and not a band across the whole texture.
std::array<TexPoint, 4> MapQuad(const PrimitiveMapping& mapping,
                                const std::array<Vec3, 4>& world_points);

// The second half of MapQuad: F1 images of the four corners unwrapped across the seam, then F2.
std::array<TexPoint, 4> UnwrapAndTransform(const PrimitiveMapping& mapping,
                                           std::array<TexPoint, 4> f1_points);

// The mapping of a curved primitive's part (side or cap) with F2 from its material.
PrimitiveMapping CurvedMapping(const CurvedPrimitive& primitive, bool cap);

}  // namespace aperture
