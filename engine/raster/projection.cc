#include "raster/projection.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "raster/polygon_clip.h"
#include "scene/shading.h"
#include "scene/triangulate.h"

namespace aperture {

void ScreenPolygon::Finalize() {
  min_x = max_x = vertices[0].x;
  min_y = max_y = vertices[0].y;
  for (const Vec2& v : vertices) {
    min_x = std::min(min_x, v.x), max_x = std::max(max_x, v.x);
    min_y = std::min(min_y, v.y), max_y = std::max(max_y, v.y);
  }
  perimeter = 0;
  for (size_t i = 0, n = vertices.size(); i < n; ++i) {
    const Vec2& p = vertices[i];
    const Vec2& q = vertices[i + 1 == n ? 0 : i + 1];
    // (The window features' sum, term for term: sqrt, not hypot.)
    perimeter += std::sqrt((q.x - p.x) * (q.x - p.x) + (q.y - p.y) * (q.y - p.y));
  }
  area = std::abs(SignedArea(vertices));
}

namespace {

// One polygon's projection: what ProjectScene keeps of scene polygon `index`, or false (behind the
// camera, outside the frustum, edge-on, a back face of a single-sided material, no area).
class PolygonProjector {
 public:
  PolygonProjector(const Scene& scene, const Camera& camera, const FrustumTangents& f, int width,
                   int height, double margin)
      : scene_(scene),
        camera_(camera),
        f_(f),
        sx_((f.right - f.left) / width),
        sy_((f.top - f.bottom) / height),
        to_camera_(camera.Orientation().Transposed()) {
    // Side planes of the frustum widened by `margin` pixels (camera space, through the origin).
    const double l = f.left - margin * sx_, r = f.right + margin * sx_;
    const double b = f.bottom - margin * sy_, t = f.top + margin * sy_;
    side_normals_[0] = {1, 0, l}, side_normals_[1] = {-1, 0, -r};
    side_normals_[2] = {0, 1, b}, side_normals_[3] = {0, -1, -t};
  }

  // Not thread-safe (scratch): one projector per thread.
  bool Project(size_t index, ScreenPolygon& sp) {
    const ScenePolygon& poly = scene_.polygons[index];
    cam_pts_.clear();
    for (const Vec3& p : poly.vertices) cam_pts_.push_back(to_camera_ * (p - camera_.position));

    const Vec3 n = to_camera_ * poly.normal;
    const double h = Dot(n, cam_pts_[0]);                                 // plane: dot(n, P) = h
    if (std::abs(h) < 1e-12 * (1.0 + Length(cam_pts_[0]))) return false;  // seen edge-on
    // h > 0: the camera is behind the polygon's front side. A single-sided material is not seen
    // from there (closed solids: their back faces never reach the visibility test).
    if (h > 0 && scene_.materials[poly.material].single_sided) return false;

    ClipByPlane(cam_pts_, {0, 0, -1}, -camera_.near, scratch3_);
    if (camera_.far > 0 && !cam_pts_.empty())
      ClipByPlane(cam_pts_, {0, 0, 1}, camera_.far, scratch3_);
    for (const Vec3& sn : side_normals_)
      if (!cam_pts_.empty()) ClipByPlane(cam_pts_, sn, 0.0, scratch3_);
    if (cam_pts_.empty()) return false;

    sp.vertices.clear();
    sp.vertices.reserve(cam_pts_.size());
    for (const Vec3& p : cam_pts_) {
      const double inv = 1.0 / -p.z;
      sp.vertices.push_back({(p.x * inv - f_.left) / sx_, (f_.top - p.y * inv) / sy_});
    }
    const double area = SignedArea(sp.vertices);
    if (std::abs(area) < 1e-12) return false;
    // Screen y points down, so counter-clockwise on screen is positive SignedArea in (x, y).
    if (area < 0) std::reverse(sp.vertices.begin(), sp.vertices.end());
    sp.Finalize();

    // Ray through (x, y): d = (left + sx x, top - sy y, -1). 1 / depth = dot(n, d) / h.
    auto linear_of = [&](const Vec3& k, double k0) {
      // dot(k, d(x, y)) + k0 as a screen-linear function.
      return ScreenLinear{k.x * sx_, -k.y * sy_, k.x * f_.left + k.y * f_.top - k.z + k0};
    };
    const ScreenLinear nd = linear_of(n, 0);
    sp.inv_depth = {nd.a / h, nd.b / h, nd.c / h};

    // seed 000, eq. 1: U = (su_c . d + u_c (1/depth)) / (1/depth), with the texture origin at
    // the camera (scene/shading.h).
    const TextureMapping& m = poly.mapping;
    const auto [uc, vc] = TextureOriginAtCamera(m, camera_.position);
    const ScreenLinear su = linear_of(to_camera_ * m.su, 0), sv = linear_of(to_camera_ * m.sv, 0);
    sp.u_num = {su.a + uc * sp.inv_depth.a, su.b + uc * sp.inv_depth.b, su.c + uc * sp.inv_depth.c};
    sp.v_num = {sv.a + vc * sp.inv_depth.a, sv.b + vc * sp.inv_depth.b, sv.c + vc * sp.inv_depth.c};

    const Material& mat = scene_.materials[poly.material];
    sp.material = poly.material;
    sp.scene_polygon = static_cast<int>(index);
    sp.layer = poly.layer;
    sp.transparent = mat.Transparent();
    // The side facing the camera is lit: every polygon is two-sided.
    sp.light = SurfaceLight(scene_, mat, h < 0 ? poly.normal : -poly.normal);
    return true;
  }

 private:
  const Scene& scene_;
  const Camera& camera_;
  const FrustumTangents& f_;
  double sx_, sy_;
  Mat3 to_camera_;
  Vec3 side_normals_[4];
  std::vector<Vec3> cam_pts_, scratch3_;
};

}  // namespace

FrameGeometry ProjectScene(const Scene& scene, const Camera& camera, int width, int height,
                           double margin) {
  FrameGeometry geo;
  geo.width = width;
  geo.height = height;
  geo.frustum = ResolveFrustum(camera, width, height);
  geo.camera_position = camera.position;
  geo.to_camera = camera.Orientation().Transposed();
  // Fixed chunks of the scene's polygons, projected in parallel (a million polygons took a
  // quarter of a second on one thread), each chunk's results kept in scene order and the chunks
  // joined in order: the geometry is the same whatever the threads. The chunks go in batches, each
  // joined before the next is projected, so that the frame's peak memory holds the polygons once
  // and a batch of them, not twice; the room reserved for all is address space until written.
  constexpr size_t kChunk = 4096, kBatch = 64 * kChunk;
  const size_t count = scene.polygons.size();
  geo.polygons.reserve(count);
  std::vector<std::vector<ScreenPolygon>> parts(kBatch / kChunk);
  tbb::enumerable_thread_specific<PolygonProjector> projectors(
      [&] { return PolygonProjector(scene, camera, geo.frustum, width, height, margin); });
  for (size_t batch = 0; batch < count; batch += kBatch) {
    const size_t end = std::min(count, batch + kBatch);
    const size_t chunks = (end - batch + kChunk - 1) / kChunk;
    tbb::parallel_for(size_t{0}, chunks, [&](size_t c) {
      PolygonProjector& projector = projectors.local();
      const size_t first = batch + c * kChunk, last = std::min(end, first + kChunk);
      std::vector<ScreenPolygon>& part = parts[c];
      part.clear();
      part.reserve(last - first);
      ScreenPolygon sp;
      for (size_t index = first; index < last; ++index)
        if (projector.Project(index, sp)) part.push_back(std::move(sp));
    });
    for (size_t c = 0; c < chunks; ++c)
      for (ScreenPolygon& sp : parts[c]) geo.polygons.push_back(std::move(sp));
  }
  return geo;
}

}  // namespace aperture
