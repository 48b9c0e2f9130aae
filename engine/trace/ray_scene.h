// The scene's primitives in an Embree 3 BVH for the corner rays of seed 003. Convex polygons are
// fanned into triangles; a hit reports the scene polygon, so corners on two triangles of one
// polygon agree. Spheres and cylinders are Embree user geometry with exact intersections
// (trace/curved_intersect).
#pragma once

#include <memory>
#include <span>
#include <vector>

#include "absl/status/statusor.h"
#include "scene/scene.h"

namespace aperture {

class RayScene {
 public:
  static absl::StatusOr<std::unique_ptr<RayScene>> Build(const Scene& scene);
  ~RayScene();
  RayScene(const RayScene&) = delete;
  RayScene& operator=(const RayScene&) = delete;

  // The primitive the ray origin + t dir, t in [t_near, t_far], meets first: a scene polygon's
  // index, or polygons + i for scene.curved[i]; -1 for none. Primitives in `skip` are passed
  // through (what lies behind a transparent surface). Thread-safe.
  int Intersect(const Vec3& origin, const Vec3& dir, double t_near, double t_far,
                std::span<const int> skip = {}) const;

  size_t triangles() const { return triangle_polygon_.size(); }
  int polygons() const { return polygons_; }

 private:
  RayScene() = default;
  // Embree works in float: vertices are stored relative to `origin_` (the scene's bounding-box
  // centre); callers recompute exact hit points in double from the polygon's plane.
  Vec3 origin_;
  void* device_ = nullptr;  // RTCDevice
  void* scene_ = nullptr;   // RTCScene
  std::vector<int> triangle_polygon_;
  int polygons_ = 0;
  unsigned triangle_geometry_ = ~0u, curved_geometry_ = ~0u;  // Embree geometry ids
  // The curved primitives moved by -origin_, read by the user-geometry callbacks.
  std::vector<CurvedPrimitive> curved_;
};

}  // namespace aperture
