#include "trace/ray_scene.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "absl/strings/str_cat.h"

namespace aperture {

absl::StatusOr<std::unique_ptr<RayScene>> RayScene::Build(const Scene& scene) {
  std::unique_ptr<RayScene> rs(new RayScene());
  Vec3 lo{INFINITY, INFINITY, INFINITY}, hi{-INFINITY, -INFINITY, -INFINITY};
  size_t vertices = 0;
  for (const ScenePolygon& p : scene.polygons) {
    vertices += p.vertices.size();
    for (const Vec3& v : p.vertices) {
      lo = {std::min(lo.x, v.x), std::min(lo.y, v.y), std::min(lo.z, v.z)};
      hi = {std::max(hi.x, v.x), std::max(hi.y, v.y), std::max(hi.z, v.z)};
    }
  }
  if (vertices > 0) rs->origin_ = (lo + hi) * 0.5;

  RTCDevice device = rtcNewDevice(nullptr);
  if (device == nullptr) return absl::InternalError("Embree: cannot create a device");
  rs->device_ = device;
  RTCScene rtc_scene = rtcNewScene(device);
  rs->scene_ = rtc_scene;
  if (vertices > 0) {
    size_t triangles = 0;
    for (const ScenePolygon& p : scene.polygons) triangles += p.vertices.size() - 2;
    RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* vb = static_cast<float*>(rtcSetNewGeometryBuffer(
        geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), vertices));
    auto* ib = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
        geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), triangles));
    if (vb == nullptr || ib == nullptr) {
      rtcReleaseGeometry(geom);
      return absl::ResourceExhaustedError("Embree: cannot allocate the geometry buffers");
    }
    rs->triangle_polygon_.reserve(triangles);
    unsigned base = 0;
    for (size_t index = 0; index < scene.polygons.size(); ++index) {
      const ScenePolygon& p = scene.polygons[index];
      for (const Vec3& v : p.vertices) {
        const Vec3 r = v - rs->origin_;
        *vb++ = static_cast<float>(r.x), *vb++ = static_cast<float>(r.y),
        *vb++ = static_cast<float>(r.z);
      }
      // The convex polygon as a fan from its first vertex.
      for (unsigned k = 1; k + 1 < p.vertices.size(); ++k) {
        *ib++ = base, *ib++ = base + k, *ib++ = base + k + 1;
        rs->triangle_polygon_.push_back(static_cast<int>(index));
      }
      base += static_cast<unsigned>(p.vertices.size());
    }
    rtcCommitGeometry(geom);
    rtcAttachGeometry(rtc_scene, geom);
    rtcReleaseGeometry(geom);
  }
  rtcCommitScene(rtc_scene);
  if (const RTCError e = rtcGetDeviceError(device); e != RTC_ERROR_NONE)
    return absl::InternalError(
        absl::StrCat("Embree: error ", static_cast<int>(e), " while building the scene"));
  return rs;
}

RayScene::~RayScene() {
  if (scene_ != nullptr) rtcReleaseScene(static_cast<RTCScene>(scene_));
  if (device_ != nullptr) rtcReleaseDevice(static_cast<RTCDevice>(device_));
}

int RayScene::Intersect(const Vec3& origin, const Vec3& dir, double t_near, double t_far) const {
  if (triangle_polygon_.empty()) return -1;
  const Vec3 o = origin - origin_;
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit rh;
  rh.ray.org_x = static_cast<float>(o.x);
  rh.ray.org_y = static_cast<float>(o.y);
  rh.ray.org_z = static_cast<float>(o.z);
  rh.ray.dir_x = static_cast<float>(dir.x);
  rh.ray.dir_y = static_cast<float>(dir.y);
  rh.ray.dir_z = static_cast<float>(dir.z);
  rh.ray.tnear = static_cast<float>(t_near);
  rh.ray.tfar =
      std::isfinite(t_far) ? static_cast<float>(t_far) : std::numeric_limits<float>::infinity();
  rh.ray.time = 0;
  rh.ray.mask = ~0u;
  rh.ray.id = 0;
  rh.ray.flags = 0;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(static_cast<RTCScene>(scene_), &context, &rh);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return -1;
  return triangle_polygon_[rh.hit.primID];
}

}  // namespace aperture
