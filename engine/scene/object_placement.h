// Placing a mesh in the world: the validated polygons of a mesh in its object's frame, the
// object's transform, and the world-space convex polygons they make. The scene builder places
// every object this way once; a per-frame update (scene_update) places a moved object again with
// the same code, so the result is what a fresh build of the moved scene would hold.
#pragma once

#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "aperture/v1/scene.pb.h"
#include "scene/scene.h"
#include "scene/vec.h"

namespace aperture {

// One mesh polygon in its object's frame, validated: distinct vertices, texture coordinates after
// the material's texture transform (seed 003's F2), the material index, and where it came from
// (the proto path, for errors).
struct LocalPolygon {
  std::vector<Vec3> vertices;
  std::vector<Vec2> uv;
  int material = 0;
  std::string where;
};

// A mesh as one object instances it (its material override and texture transforms applied).
struct ObjectMesh {
  std::vector<LocalPolygon> polygons;
  int layer = 0;  // the object's Object.layer, given to every polygon it places
};

// Where an object stands: world = linear * local + translation.
struct ObjectPlacement {
  Mat3 linear;  // rotation * scale
  Vec3 translation;
};

// The placement of a proto transform (yaw, pitch, roll, then scale; unset scale: 1, 1, 1), or an
// error naming `where` for non-finite values or a zero scale.
absl::StatusOr<ObjectPlacement> PlacementFromProto(const v1::Transform& t,
                                                   const std::string& where);

// Validates `poly` and maps its texture coordinates by the material's texture transform `tt`.
absl::StatusOr<LocalPolygon> MakeLocalPolygon(const v1::Polygon& poly, int material,
                                              const v1::TextureTransform& tt,
                                              const std::string& where);

// Appends the world-space convex polygons of `poly` placed by `placement` to `out` (concave ones
// triangulated); errors name the polygon (degenerate, not planar, self-intersecting).
absl::Status PlacePolygon(const LocalPolygon& poly, const ObjectPlacement& placement,
                          std::vector<ScenePolygon>* out);

// Every polygon of `mesh`, placed.
absl::Status PlaceMesh(const ObjectMesh& mesh, const ObjectPlacement& placement,
                       std::vector<ScenePolygon>* out);

}  // namespace aperture
