#include "raster/projection.h"

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
  edges.clear();
  for (size_t i = 0, n = vertices.size(); i < n; ++i) {
    const Vec2& p = vertices[i];
    const Vec2& q = vertices[(i + 1) % n];
    const double dx = q.x - p.x, dy = q.y - p.y;
    edges.push_back({-dy, dx, dy * p.x - dx * p.y});
  }
}

FrameGeometry ProjectScene(const Scene& scene, const Camera& camera, int width, int height,
                           double margin) {
  FrameGeometry geo;
  geo.width = width;
  geo.height = height;
  geo.frustum = ResolveFrustum(camera, width, height);
  const FrustumTangents& f = geo.frustum;
  const double sx = (f.right - f.left) / width, sy = (f.top - f.bottom) / height;
  // Side planes of the frustum widened by `margin` pixels (camera space, through the origin).
  const double l = f.left - margin * sx, r = f.right + margin * sx;
  const double b = f.bottom - margin * sy, t = f.top + margin * sy;
  const Vec3 side_normals[4] = {{1, 0, l}, {-1, 0, -r}, {0, 1, b}, {0, -1, -t}};

  const Mat3 to_camera = camera.Orientation().Transposed();
  std::vector<Vec3> cam_pts, scratch3;
  for (size_t index = 0; index < scene.polygons.size(); ++index) {
    const ScenePolygon& poly = scene.polygons[index];
    cam_pts.clear();
    for (const Vec3& p : poly.vertices) cam_pts.push_back(to_camera * (p - camera.position));

    const Vec3 n = to_camera * poly.normal;
    const double h = Dot(n, cam_pts[0]);                             // plane: dot(n, P) = h
    if (std::abs(h) < 1e-12 * (1.0 + Length(cam_pts[0]))) continue;  // seen edge-on
    // h > 0: the camera is behind the polygon's front side. A single-sided material is not seen
    // from there (closed solids: their back faces never reach the visibility test).
    if (h > 0 && scene.materials[poly.material].single_sided) continue;

    ClipByPlane(cam_pts, {0, 0, -1}, -camera.near, scratch3);
    if (camera.far > 0 && !cam_pts.empty()) ClipByPlane(cam_pts, {0, 0, 1}, camera.far, scratch3);
    for (const Vec3& sn : side_normals)
      if (!cam_pts.empty()) ClipByPlane(cam_pts, sn, 0.0, scratch3);
    if (cam_pts.empty()) continue;

    ScreenPolygon sp;
    sp.vertices.reserve(cam_pts.size());
    for (const Vec3& p : cam_pts) {
      const double inv = 1.0 / -p.z;
      sp.vertices.push_back({(p.x * inv - f.left) / sx, (f.top - p.y * inv) / sy});
    }
    const double area = SignedArea(sp.vertices);
    if (std::abs(area) < 1e-12) continue;
    // Screen y points down, so counter-clockwise on screen is positive SignedArea in (x, y).
    if (area < 0) std::reverse(sp.vertices.begin(), sp.vertices.end());
    sp.Finalize();

    // Ray through (x, y): d = (left + sx x, top - sy y, -1). 1 / depth = dot(n, d) / h.
    auto linear_of = [&](const Vec3& k, double k0) {
      // dot(k, d(x, y)) + k0 as a screen-linear function.
      return ScreenLinear{k.x * sx, -k.y * sy, k.x * f.left + k.y * f.top - k.z + k0};
    };
    const ScreenLinear nd = linear_of(n, 0);
    sp.inv_depth = {nd.a / h, nd.b / h, nd.c / h};

    // seed 000, eq. 1: U = (su_c . d + u_c (1/depth)) / (1/depth), with the texture origin at
    // the camera (scene/shading.h).
    const TextureMapping& m = poly.mapping;
    const auto [uc, vc] = TextureOriginAtCamera(m, camera.position);
    const ScreenLinear su = linear_of(to_camera * m.su, 0), sv = linear_of(to_camera * m.sv, 0);
    sp.u_num = {su.a + uc * sp.inv_depth.a, su.b + uc * sp.inv_depth.b, su.c + uc * sp.inv_depth.c};
    sp.v_num = {sv.a + vc * sp.inv_depth.a, sv.b + vc * sp.inv_depth.b, sv.c + vc * sp.inv_depth.c};

    const Material& mat = scene.materials[poly.material];
    sp.material = poly.material;
    sp.scene_polygon = static_cast<int>(index);
    sp.transparent = mat.Transparent();
    // The side facing the camera is lit: every polygon is two-sided.
    sp.light = SurfaceLight(scene, mat, h < 0 ? poly.normal : -poly.normal);
    geo.polygons.push_back(std::move(sp));
  }
  return geo;
}

}  // namespace aperture
