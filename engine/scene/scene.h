// The engine's scene: world-space convex polygons with materials, textures and lights, built from
// the proto `Scene` by scene_builder and validated there. Immutable once built.
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "absl/container/flat_hash_map.h"
#include "absl/status/statusor.h"
#include "aperture/v1/scene.pb.h"
#include "base/image.h"
#include "scene/daylight.h"
#include "scene/light_points.h"
#include "scene/vec.h"
#include "store/shared_store.h"
#include "texture/footprint_samplers.h"
#include "texture/mip_pyramid.h"
#include "texture/packed/packed_texture.h"
#include "texture/texture_sampler.h"

namespace aperture {

struct SceneTexture {
  std::string id;
  std::shared_ptr<const MipPyramid> pyramid;
  std::unique_ptr<TextureSampler> nearest, bilinear, trilinear;
  std::unique_ptr<FootprintSamplers> footprint;  // aniso (seed 000 table), oiio, reference
  // A packed vector texture (seed 001) instead of a raster: sampled in place, nearest for the
  // nearest mode, the exact area integral over the footprint for every other mode.
  std::shared_ptr<const void> packed;  // owns the bytes the samplers read (memory or the store)
  std::unique_ptr<TextureSampler> packed_nearest, packed_area;
  // Some texel has alpha below 1. Its colours are then premultiplied by alpha (OpenImageIO
  // decodes unassociated alpha, as in PNG, to associated), so every filter averages them weighted
  // by coverage, without dark fringes; shading divides the filtered colour by the filtered alpha.
  bool has_alpha = false;

  // The sampler of `mode`: the packed texture's, the mip-map's, or a footprint filter (aniso, oiio,
  // reference) built on its first use, which `stop` can stop part-way. An error naming the
  // texture and the filter when that filter cannot be built.
  absl::StatusOr<const TextureSampler*> Sampler(FilterMode mode,
                                                const std::function<bool()>& stop = nullptr) const;
};

// v1::AlphaMode: what a material's alpha (base_color.a times the texture's alpha) does.
enum class AlphaMode { kOpaque, kMask, kBlend };

struct Material {
  std::string id;
  Rgba base_color{1, 1, 1, 1};  // a: 1 - v1::Material.transparency
  int texture = -1;             // index into Scene::textures, -1: untextured
  FilterMode filter = FilterMode::kTrilinear;
  bool unlit = false;
  bool single_sided = false;  // the raster mode skips it seen from behind (v1::Material)
  AlphaMode alpha_mode = AlphaMode::kOpaque;
  float alpha_cutoff = 0.5f;  // kMask: drawn where alpha >= alpha_cutoff
  bool Transparent() const { return alpha_mode != AlphaMode::kOpaque; }
  // The alpha a surface of this material is drawn with, from its alpha there (base colour times
  // texture): 1 when opaque, 0 or 1 for MASK, within [0, 1] for BLEND.
  float ShadedAlpha(float alpha) const {
    switch (alpha_mode) {
      case AlphaMode::kOpaque:
        return 1.0f;
      case AlphaMode::kMask:
        return alpha >= alpha_cutoff ? 1.0f : 0.0f;
      case AlphaMode::kBlend:
        return alpha <= 0.0f ? 0.0f : alpha >= 1.0f ? 1.0f : alpha;
    }
    return 1.0f;
  }
};

// Affine world-to-texture map over a polygon's plane: u = dot(su, P) + u0 (texture repeats).
struct TextureMapping {
  Vec3 su, sv;
  double u0 = 0, v0 = 0;
};

// A convex planar polygon in world space (concave input is triangulated on load).
struct ScenePolygon {
  std::vector<Vec3> vertices;
  Vec3 normal;  // unit, from the vertex order
  int material = 0;
  int layer = 0;  // its object's Object.layer: which coplanar polygon is drawn over which
  TextureMapping mapping;
};

// An affine map of the texture plane, (x, z) -> (a x + b z + e, c x + d z + f): seed 003's F2
// (eq. 2), from a material's texture transform.
struct TextureAffine {
  double a = 1, b = 0, c = 0, d = 1, e = 0, f = 0;
};

enum class CurvedKind { kSphere, kCylinder };

// A sphere or a finite cylinder (seed 003's curved primitives). Only the raytrace mode draws
// them; the raster renderer refuses a scene that has any.
struct CurvedPrimitive {
  CurvedKind kind = CurvedKind::kSphere;
  Vec3 origin;  // the sphere's centre; the centre of the cylinder's base disc
  Mat3 axes;    // orthonormal, columns the frame's x, y, z in world space; y: pole / axis
  double radius = 1;
  double height = 0;  // cylinder: from the base disc along axes y
  bool capped = false;
  int material = 0;
  TextureAffine texture;  // F2 after the spherical / cylindrical F1
};

struct ObjectMesh;  // scene/object_placement.h

// A named object (the proto Object's name), which a live frame's update may move, show or hide:
// its polygons are polygons[first, first + count) (none while hidden). Objects are in the order
// the scene lists them, so are their ranges.
struct SceneObject {
  std::string name;
  size_t first = 0, count = 0;
  bool visible = true;
  v1::Transform transform;                 // the scene's or the last update's (kept while hidden)
  std::shared_ptr<const ObjectMesh> mesh;  // what placing it again needs, shared by copies
};

// A scene's hour and place (v1::TimeOfDay): its sun, ambient, sky and fog colour follow from them
// (scene/daylight.h) once it has both. A scene may give its place alone (the built-in airport):
// the hour then comes with a frame's update.
struct SceneTimeOfDay {
  std::optional<absl::Time> utc;
  GeoPlace place;
  DaylightOptions options;
  bool operator==(const SceneTimeOfDay&) const = default;
};

struct Scene {
  std::string name;
  std::vector<std::shared_ptr<const SceneTexture>> textures;
  std::vector<Material> materials;
  std::vector<ScenePolygon> polygons;
  std::vector<SceneObject> objects;  // the named ones only
  // Each named object's index in `objects`, by name: an update finds what it names in constant
  // time. Built with the scene; updates never add or remove objects, so it stays valid (and a
  // copy of the scene copies it with the objects).
  absl::flat_hash_map<std::string, size_t> object_index;
  std::vector<CurvedPrimitive> curved;  // spheres, then cylinders (raytrace mode only)
  Vec3 sun_direction{0, 1, 0};          // unit, towards the sun
  Rgba sun_color{0, 0, 0, 1};
  Rgba ambient{1, 1, 1, 1};
  Rgba fog_color{0, 0, 0, 1};
  double fog_density = 0;
  Rgba sky{0, 0, 0, 1};
  // The sky in each direction: `sky` everywhere unless the scene has a time of day.
  SkyDome sky_dome;
  std::optional<SceneTimeOfDay> time_of_day;
  SceneLights lights;  // light points (scene/light_points.h)
};

// A packed vector texture's samplers over `view`, whose bytes `owner` keeps alive.
std::shared_ptr<const SceneTexture> MakePackedSceneTexture(std::string id,
                                                           std::shared_ptr<const void> owner,
                                                           const packed::PackedTextureView& view);
std::shared_ptr<const SceneTexture> MakePackedSceneTexture(std::string id,
                                                           packed::PackedTexture texture);

// Builds a texture's pyramid (resampled to a power of two when needed) and its samplers; the
// aniso table comes from `store` when one is given.
std::shared_ptr<const SceneTexture> MakeSceneTexture(
    std::string id, Image image, std::shared_ptr<const SharedStore> store = nullptr);

}  // namespace aperture
