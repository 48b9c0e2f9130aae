#include "scene/scene_builder.h"

#include <cmath>
#include <unordered_map>

#include "absl/strings/str_cat.h"
#include "scene/object_placement.h"
#include "scene/scene_environment.h"
#include "scene/scene_textures.h"

namespace aperture {
namespace {

absl::Status Invalid(const std::string& where, const std::string& what) {
  return absl::InvalidArgumentError(absl::StrCat(where, ": ", what));
}

Vec3 FromProto(const v1::Vec3& v) { return {v.x(), v.y(), v.z()}; }

class Builder {
 public:
  Builder(const v1::Scene& proto, const SceneBuildOptions& options)
      : proto_(proto), options_(options) {}

  absl::StatusOr<Scene> Build() {
    scene_.name = proto_.name();
    if (auto s = CheckLimits(); !s.ok()) return s;
    if (auto s = BuildTextures(); !s.ok()) return s;
    if (auto s = BuildMaterials(); !s.ok()) return s;
    if (auto s = PrepareAnisoTables(); !s.ok()) return s;
    if (auto s = BuildLights(); !s.ok()) return s;
    if (auto s = BuildObjects(); !s.ok()) return s;
    if (auto s = BuildCurved(); !s.ok()) return s;
    auto lights = BuildSceneLights(proto_, scene_.object_index, options_.limits.lights);
    if (!lights.ok()) return lights.status();
    scene_.lights = *std::move(lights);
    return std::move(scene_);
  }

 private:
  bool Stopped() const { return options_.stop && options_.stop(); }
  static absl::Status StoppedError() {
    return absl::CancelledError("the scene load was stopped (deadline or cancellation)");
  }

  // The request against options_.limits, from its counts alone: nothing decoded or built yet.
  absl::Status CheckLimits() const {
    const SceneLimits& limits = options_.limits;
    if (auto lights = CountSceneLights(proto_, limits.lights); !lights.ok()) return lights.status();
    if (limits.textures > 0 && static_cast<uint64_t>(proto_.textures_size()) > limits.textures)
      return absl::InvalidArgumentError(
          absl::StrCat("textures: the scene has ", proto_.textures_size(), ", above the limit of ",
                       limits.textures, " textures per scene"));
    std::unordered_map<std::string, uint64_t> mesh_polygons;
    for (int i = 0; i < proto_.meshes_size(); ++i) {
      const v1::Mesh& mesh = proto_.meshes(i);
      mesh_polygons[mesh.id()] = static_cast<uint64_t>(mesh.polygons_size());
      if (limits.vertices_per_polygon == 0) continue;
      for (int j = 0; j < mesh.polygons_size(); ++j)
        if (static_cast<uint64_t>(mesh.polygons(j).vertices_size()) > limits.vertices_per_polygon)
          return Invalid(
              absl::StrCat("meshes[", i, "] ('", mesh.id(), "').polygons[", j, "]"),
              absl::StrCat(mesh.polygons(j).vertices_size(), " vertices, above the limit of ",
                           limits.vertices_per_polygon, " vertices per polygon"));
    }
    if (limits.polygons == 0) return absl::OkStatus();
    uint64_t polygons = 0;
    if (proto_.objects_size() == 0) {
      for (const auto& [id, count] : mesh_polygons) polygons += count;
    } else {
      for (const v1::Object& o : proto_.objects()) {
        auto it = mesh_polygons.find(o.mesh_id());
        if (it != mesh_polygons.end()) polygons += it->second;
      }
    }
    if (polygons > limits.polygons)
      return absl::InvalidArgumentError(absl::StrCat("meshes, objects: the scene places ", polygons,
                                                     " polygons, above the limit of ",
                                                     limits.polygons, " polygons per scene"));
    return absl::OkStatus();
  }

  absl::Status BuildTextures() {
    for (int i = 0; i < proto_.textures_size(); ++i) {
      if (Stopped()) return StoppedError();
      const v1::Texture& t = proto_.textures(i);
      const std::string where = absl::StrCat("textures[", i, "] ('", t.id(), "')");
      if (t.id().empty()) return Invalid(where, "texture id is empty");
      if (texture_index_.count(t.id())) return Invalid(where, "duplicate texture id");
      auto texture = BuildSceneTexture(t, where, options_);
      if (!texture.ok()) return texture.status();
      texture_index_[t.id()] = static_cast<int>(scene_.textures.size());
      scene_.textures.push_back(std::move(*texture));
    }
    return absl::OkStatus();
  }

  // The material's alpha mode, cutoff and transparency (docs/SCENE.md "Alpha").
  static absl::Status AlphaFromProto(const v1::Material& m, const std::string& where,
                                     Material& mat) {
    switch (m.alpha_mode()) {
      case v1::ALPHA_MODE_OPAQUE:
        mat.alpha_mode = AlphaMode::kOpaque;
        break;
      case v1::ALPHA_MODE_MASK:
        mat.alpha_mode = AlphaMode::kMask;
        break;
      case v1::ALPHA_MODE_BLEND:
        mat.alpha_mode = AlphaMode::kBlend;
        break;
      default:
        return Invalid(where, absl::StrCat("alpha_mode has unknown value ", m.alpha_mode()));
    }
    if (!(m.alpha_cutoff() >= 0 && m.alpha_cutoff() <= 1))
      return Invalid(where, absl::StrCat("alpha_cutoff ", m.alpha_cutoff(), " is not in [0, 1]"));
    if (!(m.transparency() >= 0 && m.transparency() <= 1))
      return Invalid(where, absl::StrCat("transparency ", m.transparency(), " is not in [0, 1]"));
    if (m.alpha_cutoff() > 0) mat.alpha_cutoff = m.alpha_cutoff();
    mat.base_color.a = 1.0f - m.transparency();
    return absl::OkStatus();
  }

  absl::Status BuildMaterials() {
    Material fallback;
    fallback.id = "";
    fallback.base_color = {0.7f, 0.7f, 0.7f, 1};
    scene_.materials.push_back(fallback);  // index 0: polygons without a material
    transforms_.push_back({});
    material_index_[""] = 0;
    for (int i = 0; i < proto_.materials_size(); ++i) {
      const v1::Material& m = proto_.materials(i);
      const std::string where = absl::StrCat("materials[", i, "] ('", m.id(), "')");
      if (m.id().empty()) return Invalid(where, "material id is empty");
      if (material_index_.count(m.id())) return Invalid(where, "duplicate material id");
      Material mat;
      mat.id = m.id();
      mat.unlit = m.unlit();
      mat.single_sided = m.single_sided();
      if (m.has_base_color()) {
        auto c = ColorFromProto(m.base_color(), where + ".base_color");
        if (!c.ok()) return c.status();
        mat.base_color = *c;
      }
      if (auto s = AlphaFromProto(m, where, mat); !s.ok()) return s;
      if (!m.texture_id().empty()) {
        auto it = texture_index_.find(m.texture_id());
        if (it == texture_index_.end())
          return absl::NotFoundError(absl::StrCat(where, ": texture_id '", m.texture_id(),
                                                  "' is not a texture of the scene"));
        mat.texture = it->second;
      }
      if (m.filter() != v1::TEXTURE_FILTER_DEFAULT) {
        const std::optional<FilterMode> filter = FilterModeFromProto(m.filter());
        if (!filter) return Invalid(where, absl::StrCat("filter has unknown value ", m.filter()));
        mat.filter = *filter;
      }
      const v1::TextureTransform& tt = m.texture_transform();
      const double values[] = {tt.repeat_u(), tt.repeat_v(), tt.rotation_deg(), tt.offset_u(),
                               tt.offset_v()};
      for (double v : values)
        if (!std::isfinite(v)) return Invalid(where, "texture_transform has a non-finite value");
      if (tt.repeat_u() < 0 || tt.repeat_v() < 0)
        return Invalid(where, "texture_transform repeats must be > 0");
      material_index_[m.id()] = static_cast<int>(scene_.materials.size());
      transforms_.push_back(tt);
      scene_.materials.push_back(mat);
    }
    return absl::OkStatus();
  }

  // With a store, tables are built (or attached) with the scene, not by its first frame.
  absl::Status PrepareAnisoTables() {
    if (!options_.store) return absl::OkStatus();
    for (const Material& m : scene_.materials) {
      if (m.filter != FilterMode::kAniso || m.texture < 0) continue;
      const SceneTexture& texture = *scene_.textures[static_cast<size_t>(m.texture)];
      if (!texture.footprint) continue;  // packed textures have no table
      if (auto s = texture.footprint->PrepareAniso(options_.stop); !s.ok()) {
        if (absl::IsCancelled(s)) return StoppedError();
        return absl::Status(s.code(), absl::StrCat("materials ('", m.id, "'): texture '",
                                                   texture.id, "': ", s.message()));
      }
    }
    return absl::OkStatus();
  }

  absl::Status BuildLights() {
    if (proto_.has_sun())
      if (auto s = SetSun(proto_.sun(), &scene_); !s.ok()) return s;
    if (proto_.has_ambient()) {
      if (auto s = SetAmbient(proto_.ambient(), &scene_); !s.ok()) return s;
    } else if (proto_.has_sun()) {
      scene_.ambient = {0, 0, 0, 1};
    }
    if (proto_.has_fog())
      if (auto s = SetFog(proto_.fog(), &scene_); !s.ok()) return s;
    if (proto_.has_sky())
      if (auto s = SetSky(proto_.sky(), &scene_); !s.ok()) return s;
    if (proto_.has_time_of_day())  // over the sun, ambient, sky and fog colour above
      return SetTimeOfDay(proto_.time_of_day(), /*update=*/false, "time_of_day", &scene_);
    return absl::OkStatus();
  }

  absl::Status BuildObjects() {
    std::unordered_map<std::string, int> mesh_index;
    for (int i = 0; i < proto_.meshes_size(); ++i) {
      const std::string& id = proto_.meshes(i).id();
      const std::string where = absl::StrCat("meshes[", i, "] ('", id, "')");
      if (id.empty()) return Invalid(where, "mesh id is empty");
      if (mesh_index.count(id)) return Invalid(where, "duplicate mesh id");
      mesh_index[id] = i;
    }
    if (proto_.objects_size() == 0) {  // no objects: every mesh once, untransformed
      for (int i = 0; i < proto_.meshes_size(); ++i) {
        if (Stopped()) return StoppedError();
        auto mesh = MakeObjectMesh(i, "", absl::StrCat("meshes[", i, "]"));
        if (!mesh.ok()) return mesh.status();
        if (auto s = PlaceMesh(*mesh, ObjectPlacement{}, &scene_.polygons); !s.ok()) return s;
      }
      return absl::OkStatus();
    }
    std::unordered_map<std::string, int> object_names;
    for (int i = 0; i < proto_.objects_size(); ++i) {
      if ((i & 255) == 0 && Stopped()) return StoppedError();
      const v1::Object& o = proto_.objects(i);
      const std::string where = absl::StrCat("objects[", i, "]");
      auto it = mesh_index.find(o.mesh_id());
      if (it == mesh_index.end())
        return absl::NotFoundError(
            absl::StrCat(where, ": mesh_id '", o.mesh_id(), "' is not a mesh of the scene"));
      if (!o.name().empty() && !object_names.emplace(o.name(), i).second)
        return Invalid(where, absl::StrCat("duplicate object name '", o.name(), "'"));
      if (o.hidden() && o.name().empty())
        return Invalid(where, "a hidden object needs a name (an update shows it)");
      auto placement = PlacementFromProto(o.transform(), where);
      if (!placement.ok()) return placement.status();
      auto mesh = MakeObjectMesh(it->second, o.material_id(),
                                 absl::StrCat(where, " mesh '", o.mesh_id(), "'"));
      if (!mesh.ok()) return mesh.status();
      mesh->layer = o.layer();
      if (o.name().empty()) {
        if (auto s = PlaceMesh(*mesh, *placement, &scene_.polygons); !s.ok()) return s;
        continue;
      }
      // Named: placed (and so validated) even when hidden, and kept for updates.
      std::vector<ScenePolygon> placed;
      if (auto s = PlaceMesh(*mesh, *placement, &placed); !s.ok()) return s;
      SceneObject object;
      object.name = o.name();
      object.first = scene_.polygons.size();
      object.visible = !o.hidden();
      object.transform = o.transform();
      object.mesh = std::make_shared<const ObjectMesh>(*std::move(mesh));
      if (object.visible) {
        object.count = placed.size();
        for (ScenePolygon& p : placed) scene_.polygons.push_back(std::move(p));
      }
      scene_.object_index.emplace(object.name, scene_.objects.size());
      scene_.objects.push_back(std::move(object));
    }
    return absl::OkStatus();
  }

  absl::StatusOr<int> MaterialIndex(const std::string& id, const std::string& where) {
    auto it = material_index_.find(id);
    if (it == material_index_.end())
      return absl::NotFoundError(
          absl::StrCat(where, ": material_id '", id, "' is not a material of the scene"));
    return it->second;
  }

  // The polygons of mesh `mesh` in its object's frame, validated, with their materials.
  absl::StatusOr<ObjectMesh> MakeObjectMesh(int mesh, const std::string& material_override,
                                            const std::string& where_object) {
    const v1::Mesh& m = proto_.meshes(mesh);
    ObjectMesh out;
    out.polygons.reserve(static_cast<size_t>(m.polygons_size()));
    for (int p = 0; p < m.polygons_size(); ++p) {
      const v1::Polygon& poly = m.polygons(p);
      const std::string where = absl::StrCat(where_object, ".polygons[", p, "]");
      std::string material_id = !material_override.empty()    ? material_override
                                : !poly.material_id().empty() ? poly.material_id()
                                                              : m.material_id();
      auto material = MaterialIndex(material_id, where);
      if (!material.ok()) return material.status();
      auto local = MakeLocalPolygon(poly, *material, transforms_[*material], where);
      if (!local.ok()) return local.status();
      out.polygons.push_back(*std::move(local));
    }
    return out;
  }

  // Spheres, then cylinders, each with its frame and the material's texture transform as F2.
  absl::Status BuildCurved() {
    for (int i = 0; i < proto_.spheres_size(); ++i) {
      const v1::Sphere& sp = proto_.spheres(i);
      const std::string where = absl::StrCat("spheres[", i, "]");
      CurvedPrimitive c;
      c.kind = CurvedKind::kSphere;
      c.origin = FromProto(sp.center());
      if (!IsFinite(c.origin)) return Invalid(where + ".center", "coordinate is NaN or infinite");
      if (auto s = CheckRadius(sp.radius(), where); !s.ok()) return s;
      c.radius = sp.radius();
      const Vec3 pole = sp.has_pole() ? FromProto(sp.pole()) : Vec3{0, 1, 0};
      if (!IsFinite(pole) || !(Length(pole) > 0))
        return Invalid(where + ".pole", "must be a finite non-zero direction");
      c.axes = FrameAround(pole);
      if (auto s = SetCurvedMaterial(sp.material_id(), where, &c); !s.ok()) return s;
      scene_.curved.push_back(c);
    }
    for (int i = 0; i < proto_.cylinders_size(); ++i) {
      const v1::Cylinder& cy = proto_.cylinders(i);
      const std::string where = absl::StrCat("cylinders[", i, "]");
      CurvedPrimitive c;
      c.kind = CurvedKind::kCylinder;
      c.origin = FromProto(cy.base());
      const Vec3 top = FromProto(cy.top());
      if (!IsFinite(c.origin)) return Invalid(where + ".base", "coordinate is NaN or infinite");
      if (!IsFinite(top)) return Invalid(where + ".top", "coordinate is NaN or infinite");
      if (auto s = CheckRadius(cy.radius(), where); !s.ok()) return s;
      c.radius = cy.radius();
      c.height = Length(top - c.origin);
      if (!(c.height > 0) || !std::isfinite(c.height))
        return Invalid(where + ".top", "must differ from base (the cylinder has no length)");
      c.axes = FrameAround(top - c.origin);
      c.capped = cy.capped();
      if (auto s = SetCurvedMaterial(cy.material_id(), where, &c); !s.ok()) return s;
      scene_.curved.push_back(c);
    }
    return absl::OkStatus();
  }

  static absl::Status CheckRadius(double radius, const std::string& where) {
    if (!std::isfinite(radius)) return Invalid(where + ".radius", "is NaN or infinite");
    if (!(radius > 0)) return Invalid(where + ".radius", absl::StrCat("must be > 0, is ", radius));
    return absl::OkStatus();
  }

  // An orthonormal frame whose y is `axis`: (x, y, z) = identity for +y.
  static Mat3 FrameAround(const Vec3& axis) {
    const Vec3 y = Normalize(axis);
    const Vec3 helper = std::abs(y.x) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 0, -1};
    const Vec3 z = Normalize(Cross(helper, y));
    const Vec3 x = Cross(y, z);
    Mat3 m;
    const Vec3 cols[3] = {x, y, z};
    for (int j = 0; j < 3; ++j) m.m[0][j] = cols[j].x, m.m[1][j] = cols[j].y, m.m[2][j] = cols[j].z;
    return m;
  }

  // seed 003's F2 from the material's texture transform: rotation, then repeats and shift.
  absl::Status SetCurvedMaterial(const std::string& id, const std::string& where,
                                 CurvedPrimitive* c) {
    auto material = MaterialIndex(id, where);
    if (!material.ok()) return material.status();
    c->material = *material;
    const v1::TextureTransform& tt = transforms_[*material];
    const double ru = tt.repeat_u() > 0 ? tt.repeat_u() : 1.0;
    const double rv = tt.repeat_v() > 0 ? tt.repeat_v() : ru;
    const double cr = std::cos(Radians(tt.rotation_deg())),
                 sr = std::sin(Radians(tt.rotation_deg()));
    c->texture = {cr / ru, -sr / ru, sr / rv, cr / rv, tt.offset_u(), tt.offset_v()};
    return absl::OkStatus();
  }

  const v1::Scene& proto_;
  const SceneBuildOptions& options_;
  Scene scene_;
  std::unordered_map<std::string, int> texture_index_, material_index_;
  std::vector<v1::TextureTransform> transforms_;
};

}  // namespace

absl::StatusOr<Scene> BuildScene(const v1::Scene& proto, const SceneBuildOptions& options) {
  // glTF model references are resolved where the scene file is read (import/gltf_import.h,
  // ExpandModels): a scene here, from a request or a file already read, carries them as meshes.
  if (proto.models_size() > 0)
    return absl::InvalidArgumentError(absl::StrCat(
        "models[0] ('", proto.models(0).id(),
        "'): glTF model references are resolved when a scene file is read (aperture-render, the "
        "client); a scene sent to the service carries the models' meshes"));
  for (int i = 0; i < proto.objects_size(); ++i)
    if (!proto.objects(i).model_id().empty())
      return absl::InvalidArgumentError(absl::StrCat("objects[", i, "].model_id: '",
                                                     proto.objects(i).model_id(),
                                                     "' is not resolved: the scene has no models"));
  return Builder(proto, options).Build();
}

}  // namespace aperture
