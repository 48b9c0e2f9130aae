#include "scene/object_placement.h"

#include <cmath>

#include "absl/strings/str_cat.h"
#include "scene/simple_polygon.h"
#include "scene/triangulate.h"

namespace aperture {
namespace {

absl::Status Invalid(const std::string& where, const std::string& what) {
  return absl::InvalidArgumentError(absl::StrCat(where, ": ", what));
}

Vec3 FromProto(const v1::Vec3& v) { return {v.x(), v.y(), v.z()}; }

// Where no uvs are given: project onto the world axis plane the polygon faces most.
// Walls use -y as t so that images stand upright.
Vec2 PlanarProjection(const Vec3& p, const Vec3& n) {
  const double ax = std::abs(n.x), ay = std::abs(n.y), az = std::abs(n.z);
  if (ay >= ax && ay >= az) return {p.x, p.z};
  if (az >= ax) return {p.x, -p.y};
  return {p.z, -p.y};
}

// Fits the affine map world -> (s, t) over the polygon's plane from three well-spread vertices.
void FitMapping(const std::vector<Vec3>& pts, const std::vector<Vec2>& st, const Vec3& normal,
                Vec3* ss, Vec3* tt, double* s0, double* t0) {
  size_t i1 = 1, i2 = 2;
  double best = -1;
  for (size_t i = 1; i < pts.size(); ++i) {
    double d = Length(pts[i] - pts[0]);
    if (d > best) best = d, i1 = i;
  }
  best = -1;
  for (size_t i = 1; i < pts.size(); ++i) {
    double a = Length(Cross(pts[i1] - pts[0], pts[i] - pts[0]));
    if (a > best) best = a, i2 = i;
  }
  const Vec3 e1 = pts[i1] - pts[0], e2 = pts[i2] - pts[0];
  // Dual basis within the plane: dot(g1, e1) = 1, dot(g1, e2) = 0, and likewise for g2.
  const Vec3 c2 = Cross(e2, normal), c1 = Cross(normal, e1);
  const Vec3 g1 = c2 * (1.0 / Dot(e1, c2)), g2 = c1 * (1.0 / Dot(e2, c1));
  const double ds1 = st[i1].x - st[0].x, ds2 = st[i2].x - st[0].x;
  const double dt1 = st[i1].y - st[0].y, dt2 = st[i2].y - st[0].y;
  *ss = g1 * ds1 + g2 * ds2;
  *tt = g1 * dt1 + g2 * dt2;
  *s0 = st[0].x - Dot(*ss, pts[0]);
  *t0 = st[0].y - Dot(*tt, pts[0]);
}

// Newell's normal (length = twice the area): robust for any planar polygon, convex or not.
Vec3 NewellNormal(const std::vector<Vec3>& pts) {
  Vec3 n;
  for (size_t i = 0; i < pts.size(); ++i) {
    const Vec3& a = pts[i];
    const Vec3& b = pts[(i + 1) % pts.size()];
    n = n + Vec3{(a.y - b.y) * (a.z + b.z), (a.z - b.z) * (a.x + b.x), (a.x - b.x) * (a.y + b.y)};
  }
  return n;
}

}  // namespace

absl::StatusOr<ObjectPlacement> PlacementFromProto(const v1::Transform& t,
                                                   const std::string& where) {
  ObjectPlacement placement;
  const Vec3 scale = t.has_scale() ? FromProto(t.scale()) : Vec3{1, 1, 1};
  placement.translation = FromProto(t.translation());
  const double angles[] = {t.yaw_deg(), t.pitch_deg(), t.roll_deg()};
  for (double a : angles)
    if (!std::isfinite(a)) return Invalid(where, "transform angles are not finite");
  if (!IsFinite(placement.translation))
    return Invalid(where, "transform translation is not finite");
  if (!IsFinite(scale) || scale.x == 0 || scale.y == 0 || scale.z == 0)
    return Invalid(where, "transform scale must be finite and non-zero");
  placement.linear = YawPitchRoll(t.yaw_deg(), t.pitch_deg(), t.roll_deg()) * Mat3::Scale(scale);
  return placement;
}

absl::StatusOr<LocalPolygon> MakeLocalPolygon(const v1::Polygon& poly, int material,
                                              const v1::TextureTransform& tt,
                                              const std::string& where) {
  if (poly.vertices_size() < 3)
    return Invalid(
        where, absl::StrCat("polygon has ", poly.vertices_size(), " vertices, needs at least 3"));
  if (poly.uvs_size() != 0 && poly.uvs_size() != poly.vertices_size())
    return Invalid(where, absl::StrCat("polygon has ", poly.uvs_size(), " uvs for ",
                                       poly.vertices_size(), " vertices"));
  LocalPolygon local;
  local.material = material;
  local.where = where;
  std::vector<Vec3>& vertices = local.vertices;
  std::vector<Vec2>& uv = local.uv;
  for (int i = 0; i < poly.vertices_size(); ++i) {
    const Vec3 v = FromProto(poly.vertices(i));
    if (!IsFinite(v))
      return Invalid(absl::StrCat(where, ".vertices[", i, "]"), "coordinate is NaN or infinite");
    Vec2 t;
    if (poly.uvs_size() != 0) {
      t = {poly.uvs(i).u(), poly.uvs(i).v()};
      if (!std::isfinite(t.x) || !std::isfinite(t.y))
        return Invalid(absl::StrCat(where, ".uvs[", i, "]"), "is NaN or infinite");
    }
    if (!vertices.empty() && vertices.back() == v) continue;  // repeated vertex
    vertices.push_back(v);
    uv.push_back(t);
  }
  while (vertices.size() > 1 && vertices.front() == vertices.back())
    vertices.pop_back(), uv.pop_back();
  if (vertices.size() < 3) return Invalid(where, "polygon has fewer than 3 distinct vertices");

  if (poly.uvs_size() == 0) {
    const Vec3 ln = NewellNormal(vertices);
    for (size_t i = 0; i < vertices.size(); ++i) uv[i] = PlanarProjection(vertices[i], ln);
  }
  // seed 003's F2: rotation, scale (repeats) and shift in the texture plane.
  const double ru = tt.repeat_u() > 0 ? tt.repeat_u() : 1.0;
  const double rv = tt.repeat_v() > 0 ? tt.repeat_v() : ru;
  const double cr = std::cos(Radians(tt.rotation_deg())), sr = std::sin(Radians(tt.rotation_deg()));
  for (Vec2& t : uv)
    t = {(cr * t.x - sr * t.y) / ru + tt.offset_u(), (sr * t.x + cr * t.y) / rv + tt.offset_v()};
  return local;
}

absl::Status PlacePolygon(const LocalPolygon& poly, const ObjectPlacement& placement,
                          std::vector<ScenePolygon>* out) {
  const std::vector<Vec3>& local = poly.vertices;
  std::vector<Vec3> world(local.size());
  for (size_t i = 0; i < local.size(); ++i)
    world[i] = placement.linear * local[i] + placement.translation;

  // Far enough for any simulated world, near enough that products of coordinates (areas,
  // normals) stay far from overflow and a camera-relative vertex keeps micrometres (the spacing
  // of doubles at 1e8 is 1.5e-8).
  constexpr double kMaxCoordinate = 1e8;
  for (size_t i = 0; i < world.size(); ++i)
    if (!(std::abs(world[i].x) <= kMaxCoordinate && std::abs(world[i].y) <= kMaxCoordinate &&
          std::abs(world[i].z) <= kMaxCoordinate))
      return Invalid(
          poly.where,
          absl::StrCat("vertex ", i, " is at (", world[i].x, ", ", world[i].y, ", ", world[i].z,
                       ") m after its object's transform: coordinates are limited "
                       "to +-1e8 m"));
  const Vec3 newell = NewellNormal(world);
  double extent = 0;
  for (const Vec3& v : world) extent = std::max(extent, Length(v - world[0]));
  const double twice_area = Length(newell);
  if (!(twice_area > 1e-12 * extent * extent) || extent == 0)
    return Invalid(poly.where,
                   "polygon is degenerate (zero area: collinear or coincident vertices)");
  const Vec3 normal = newell * (1.0 / twice_area);
  for (const Vec3& v : world)
    if (std::abs(Dot(normal, v - world[0])) > 1e-6 * extent)
      return Invalid(poly.where, "polygon is not planar");

  ScenePolygon base;
  base.normal = normal;
  base.material = poly.material;
  FitMapping(world, poly.uv, normal, &base.mapping.su, &base.mapping.sv, &base.mapping.u0,
             &base.mapping.v0);

  // Convexity and triangulation in the 2D plane the polygon faces most.
  std::vector<Vec2> flat(world.size());
  for (size_t i = 0; i < world.size(); ++i) {
    const double ax = std::abs(normal.x), ay = std::abs(normal.y), az = std::abs(normal.z);
    flat[i] = (az >= ax && az >= ay) ? Vec2{world[i].x, world[i].y}
              : (ay >= ax)           ? Vec2{world[i].z, world[i].x}
                                     : Vec2{world[i].y, world[i].z};
  }
  // A convex polygon is simple; any other is checked before it is cut into triangles.
  const bool convex = IsConvex(flat);
  if (!convex)
    if (auto simple = CheckSimplePolygon(flat); !simple.ok())
      return Invalid(poly.where, std::string(simple.message()));
  if (convex) {
    base.vertices = std::move(world);
    out->push_back(std::move(base));
    return absl::OkStatus();
  }
  auto triangles = TriangulatePolygon(flat);
  if (!triangles.ok()) return Invalid(poly.where, std::string(triangles.status().message()));
  for (const auto& tri : *triangles) {
    ScenePolygon piece = base;
    piece.vertices = {world[tri[0]], world[tri[1]], world[tri[2]]};
    out->push_back(std::move(piece));
  }
  return absl::OkStatus();
}

absl::Status PlaceMesh(const ObjectMesh& mesh, const ObjectPlacement& placement,
                       std::vector<ScenePolygon>* out) {
  const size_t first = out->size();
  for (const LocalPolygon& poly : mesh.polygons)
    if (auto s = PlacePolygon(poly, placement, out); !s.ok()) return s;
  for (size_t i = first; i < out->size(); ++i) (*out)[i].layer = mesh.layer;
  return absl::OkStatus();
}

}  // namespace aperture
