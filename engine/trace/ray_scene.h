// The scene's polygons in an Embree 3 BVH for the corner rays of seed 003. Convex polygons are
// fanned into triangles; a hit reports the scene polygon, so corners on two triangles of one
// polygon agree.
#pragma once

#include <memory>
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

  // The scene polygon the ray origin + t dir, t in [t_near, t_far], meets first; -1 for none.
  // Thread-safe.
  int Intersect(const Vec3& origin, const Vec3& dir, double t_near, double t_far) const;

  size_t triangles() const { return triangle_polygon_.size(); }

 private:
  RayScene() = default;
  // Embree works in float: vertices are stored relative to `origin_` (the scene's bounding-box
  // centre); callers recompute exact hit points in double from the polygon's plane.
  Vec3 origin_;
  void* device_ = nullptr;  // RTCDevice
  void* scene_ = nullptr;   // RTCScene
  std::vector<int> triangle_polygon_;
};

}  // namespace aperture
