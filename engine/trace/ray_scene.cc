#include "trace/ray_scene.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "absl/strings/str_cat.h"
#include "trace/curved_intersect.h"

namespace aperture {
namespace {

// Embree user geometry over RayScene::curved_ (origin-relative, float rays from rtcIntersect1).
void CurvedBoundsCallback(const RTCBoundsFunctionArguments* args) {
  const auto& curved = *static_cast<const std::vector<CurvedPrimitive>*>(args->geometryUserPtr);
  Vec3 lo, hi;
  CurvedBounds(curved[args->primID], &lo, &hi);
  // Padded by a little more than float rounding, so that grazing rays are not culled.
  const double pad = 1e-5 * (1 + std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z}));
  args->bounds_o->lower_x = static_cast<float>(lo.x - pad);
  args->bounds_o->lower_y = static_cast<float>(lo.y - pad);
  args->bounds_o->lower_z = static_cast<float>(lo.z - pad);
  args->bounds_o->upper_x = static_cast<float>(hi.x + pad);
  args->bounds_o->upper_y = static_cast<float>(hi.y + pad);
  args->bounds_o->upper_z = static_cast<float>(hi.z + pad);
}

// Only rtcIntersect1 is used: N is 1 and the ray is an RTCRayHit.
void CurvedIntersectCallback(const RTCIntersectFunctionNArguments* args) {
  if (args->N != 1 || args->valid[0] == 0) return;
  const auto& curved = *static_cast<const std::vector<CurvedPrimitive>*>(args->geometryUserPtr);
  RTCRayHit* rh = reinterpret_cast<RTCRayHit*>(args->rayhit);
  const Vec3 o{rh->ray.org_x, rh->ray.org_y, rh->ray.org_z};
  const Vec3 d{rh->ray.dir_x, rh->ray.dir_y, rh->ray.dir_z};
  const auto hit = IntersectCurved(curved[args->primID], o, d, rh->ray.tnear, rh->ray.tfar);
  if (!hit) return;
  rh->ray.tfar = static_cast<float>(hit->t);
  rh->hit.Ng_x = static_cast<float>(hit->normal.x);
  rh->hit.Ng_y = static_cast<float>(hit->normal.y);
  rh->hit.Ng_z = static_cast<float>(hit->normal.z);
  rh->hit.u = rh->hit.v = 0;
  rh->hit.primID = args->primID;
  rh->hit.geomID = args->geomID;
  rh->hit.instID[0] = args->context->instID[0];
}

void CurvedOccludedCallback(const RTCOccludedFunctionNArguments* args) {
  if (args->N != 1 || args->valid[0] == 0) return;
  const auto& curved = *static_cast<const std::vector<CurvedPrimitive>*>(args->geometryUserPtr);
  RTCRay* ray = reinterpret_cast<RTCRay*>(args->ray);
  const Vec3 o{ray->org_x, ray->org_y, ray->org_z}, d{ray->dir_x, ray->dir_y, ray->dir_z};
  if (IntersectCurved(curved[args->primID], o, d, ray->tnear, ray->tfar))
    ray->tfar = -std::numeric_limits<float>::infinity();
}

}  // namespace

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
  for (const CurvedPrimitive& c : scene.curved) {
    Vec3 clo, chi;
    CurvedBounds(c, &clo, &chi);
    lo = {std::min(lo.x, clo.x), std::min(lo.y, clo.y), std::min(lo.z, clo.z)};
    hi = {std::max(hi.x, chi.x), std::max(hi.y, chi.y), std::max(hi.z, chi.z)};
  }
  if (vertices > 0 || !scene.curved.empty()) rs->origin_ = (lo + hi) * 0.5;
  rs->polygons_ = static_cast<int>(scene.polygons.size());

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
    rs->triangle_geometry_ = rtcAttachGeometry(rtc_scene, geom);
    rtcReleaseGeometry(geom);
  }
  if (!scene.curved.empty()) {
    rs->curved_ = scene.curved;
    for (CurvedPrimitive& c : rs->curved_) c.origin = c.origin - rs->origin_;
    RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_USER);
    rtcSetGeometryUserPrimitiveCount(geom, static_cast<unsigned>(rs->curved_.size()));
    rtcSetGeometryUserData(geom, &rs->curved_);
    rtcSetGeometryBoundsFunction(geom, CurvedBoundsCallback, nullptr);
    rtcSetGeometryIntersectFunction(geom, CurvedIntersectCallback);
    rtcSetGeometryOccludedFunction(geom, CurvedOccludedCallback);
    rtcCommitGeometry(geom);
    rs->curved_geometry_ = rtcAttachGeometry(rtc_scene, geom);
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

int RayScene::Intersect(const Vec3& origin, const Vec3& dir, double t_near, double t_far,
                        std::span<const int> skip) const {
  if (triangle_polygon_.empty() && curved_.empty()) return -1;
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
  const float far = rh.ray.tfar;
  // A skipped primitive's hit moves the ray's start just past it; a polygon's other triangles
  // and a curved primitive's far side may be met again, so a few rounds can be needed.
  for (int round = 0; round < 64; ++round) {
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(static_cast<RTCScene>(scene_), &context, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return -1;
    const int hit = rh.hit.geomID == curved_geometry_ ? polygons_ + static_cast<int>(rh.hit.primID)
                                                      : triangle_polygon_[rh.hit.primID];
    if (std::find(skip.begin(), skip.end(), hit) == skip.end()) return hit;
    rh.ray.tnear = std::nextafter(rh.ray.tfar, far);
    rh.ray.tfar = far;
    if (!(rh.ray.tnear < far)) return -1;
  }
  return -1;
}

}  // namespace aperture
