#include "gltf_import.h"

#include <tiny_gltf.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <map>
#include <numbers>
#include <optional>
#include <set>
#include <tuple>

#include "absl/strings/ascii.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_join.h"
#include "gltf_accessor.h"
#include "gltf_json_structure.h"
#include "gltf_node_tree.h"
#include "gltf_triangle_count.h"

namespace aperture {
namespace {

namespace fs = std::filesystem;

// Column-major 4 x 4, as glTF stores node matrices.
using Mat4 = std::array<double, 16>;

constexpr Mat4 kIdentity = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};

Mat4 Multiply(const Mat4& a, const Mat4& b) {
  Mat4 m{};
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) {
      double sum = 0;
      for (int k = 0; k < 4; ++k) sum += a[k * 4 + r] * b[c * 4 + k];
      m[c * 4 + r] = sum;
    }
  return m;
}

std::array<double, 3> Apply(const Mat4& m, const std::array<double, 3>& p) {
  std::array<double, 3> out;
  for (int r = 0; r < 3; ++r) out[r] = m[r] * p[0] + m[4 + r] * p[1] + m[8 + r] * p[2] + m[12 + r];
  return out;
}

absl::Status Invalid(const std::string& where, const std::string& what) {
  return absl::InvalidArgumentError(absl::StrCat(where, ": ", what));
}

// The node's own transform: its matrix, else translation * rotation * scale.
absl::StatusOr<Mat4> LocalTransform(const tinygltf::Node& node, const std::string& where) {
  if (!node.matrix.empty()) {
    if (node.matrix.size() != 16) return Invalid(where + ".matrix", "needs 16 numbers");
    Mat4 m;
    std::copy(node.matrix.begin(), node.matrix.end(), m.begin());
    for (double v : m)
      if (!std::isfinite(v)) return Invalid(where + ".matrix", "is NaN or infinite");
    return m;
  }
  Mat4 m = kIdentity;
  double x = 0, y = 0, z = 0, w = 1;
  if (!node.rotation.empty()) {
    if (node.rotation.size() != 4) return Invalid(where + ".rotation", "needs 4 numbers");
    x = node.rotation[0], y = node.rotation[1], z = node.rotation[2], w = node.rotation[3];
    const double norm = std::sqrt(x * x + y * y + z * z + w * w);
    if (!(norm > 0) || !std::isfinite(norm))
      return Invalid(where + ".rotation", "is not a rotation quaternion");
    x /= norm, y /= norm, z /= norm, w /= norm;
  }
  // The rotation matrix of the unit quaternion, columns scaled.
  std::array<double, 3> s = {1, 1, 1}, t = {0, 0, 0};
  if (!node.scale.empty()) {
    if (node.scale.size() != 3) return Invalid(where + ".scale", "needs 3 numbers");
    s = {node.scale[0], node.scale[1], node.scale[2]};
  }
  if (!node.translation.empty()) {
    if (node.translation.size() != 3) return Invalid(where + ".translation", "needs 3 numbers");
    t = {node.translation[0], node.translation[1], node.translation[2]};
  }
  const double r[3][3] = {{1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)},
                          {2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)},
                          {2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)}};
  for (int c = 0; c < 3; ++c)
    for (int row = 0; row < 3; ++row) m[c * 4 + row] = r[row][c] * s[c];
  for (int row = 0; row < 3; ++row) m[12 + row] = t[row];
  for (double v : m)
    if (!std::isfinite(v)) return Invalid(where, "transform is NaN or infinite");
  return m;
}

// The uv map of KHR_texture_transform: offset, rotation, scale.
struct UvTransform {
  double offset[2] = {0, 0}, rotation = 0, scale[2] = {1, 1};
  std::array<double, 2> Apply(double u, double v) const {
    // The extension's matrix: translation * rotation * scale, rotation clockwise in uv space.
    const double su = u * scale[0], sv = v * scale[1];
    const double c = std::cos(rotation), s = std::sin(rotation);
    return {c * su + s * sv + offset[0], -s * su + c * sv + offset[1]};
  }
};

UvTransform TextureTransformOf(const tinygltf::TextureInfo& info) {
  UvTransform t;
  const auto it = info.extensions.find("KHR_texture_transform");
  if (it == info.extensions.end() || !it->second.IsObject()) return t;
  const tinygltf::Value& ext = it->second;
  auto number = [](const tinygltf::Value& v) { return v.IsNumber() ? v.GetNumberAsDouble() : 0.0; };
  if (ext.Has("offset") && ext.Get("offset").ArrayLen() == 2)
    t.offset[0] = number(ext.Get("offset").Get(0)), t.offset[1] = number(ext.Get("offset").Get(1));
  if (ext.Has("scale") && ext.Get("scale").ArrayLen() == 2)
    t.scale[0] = number(ext.Get("scale").Get(0)), t.scale[1] = number(ext.Get("scale").Get(1));
  if (ext.Has("rotation")) t.rotation = number(ext.Get("rotation"));
  return t;
}

// Camera orientation from a rotation matrix (columns: the camera's axes in the world):
// R = Ry(yaw) Rx(pitch) Rz(-roll), as scene/vec.h's YawPitchRoll.
void SetOrientation(const double r[3][3], v1::Camera& camera) {
  constexpr double kDeg = 180.0 / std::numbers::pi;
  const double pitch = std::asin(std::clamp(-r[1][2], -1.0, 1.0));
  double yaw, roll;
  if (std::abs(std::cos(pitch)) > 1e-9) {
    yaw = std::atan2(r[0][2], r[2][2]);
    roll = -std::atan2(r[1][0], r[1][1]);
  } else {  // looking straight up or down: the roll folds into the yaw
    yaw = std::atan2(-r[2][0], r[0][0]);
    roll = 0;
  }
  camera.set_yaw_deg(yaw * kDeg);
  camera.set_pitch_deg(pitch * kDeg);
  camera.set_roll_deg(roll * kDeg);
}

class Importer {
 public:
  Importer(const tinygltf::Model& model,
           const std::map<int, std::vector<unsigned char>>& image_bytes,
           const GltfImportOptions& options)
      : model_(model), image_bytes_(image_bytes), options_(options) {}

  absl::StatusOr<ImportedModel> Run(const std::string& name) {
    out_.scene.set_name(name);
    // The node graph is a forest and the triangles fit the budget before anything is built.
    auto tree = NodeTree::Check(model_);
    if (!tree.ok()) return tree.status();
    std::vector<int> roots;
    if (model_.defaultScene >= static_cast<int>(model_.scenes.size()))
      return Invalid("scene", absl::StrCat("scene ", model_.defaultScene, " does not exist (",
                                           model_.scenes.size(), " scenes)"));
    if (model_.defaultScene >= 0)
      roots = model_.scenes[model_.defaultScene].nodes;
    else if (!model_.scenes.empty())
      roots = model_.scenes[0].nodes;
    else
      roots = tree->Roots();
    const std::vector<int> nodes = tree->DepthFirst(roots);
    auto triangles = CountTriangles(model_, nodes);
    if (!triangles.ok()) return triangles.status();
    if (*triangles > options_.max_triangles)
      return absl::InvalidArgumentError(absl::StrCat(
          "the model's nodes place ", *triangles,
          " triangles (a mesh counted once for each node that places it), above the budget of ",
          options_.max_triangles, " triangles per model"));
    if (auto s = Materials(); !s.ok()) return s;
    // Parents come before their children in `nodes`: each node's world transform is its
    // parent's times its own.
    std::vector<Mat4> world(model_.nodes.size());
    for (const int node : nodes) {
      const int parent = tree->parent(node);
      if (auto s = Visit(node, parent >= 0 ? world[parent] : kIdentity, world[node]); !s.ok())
        return s;
    }
    Note(dropped_degenerate_, "degenerate triangles (zero area) skipped");
    Note(static_cast<int>(model_.skins.size()), "skins ignored: meshes drawn in their bind pose");
    Note(static_cast<int>(model_.animations.size()), "animations ignored");
    Note(morph_targets_, "primitives' morph targets ignored");
    Note(points_or_lines_, "point or line primitives not drawn");
    Note(orthographic_, "orthographic cameras not supported");
    Note(directional_lights_, "directional lights ignored (a light point has a position)");
    Note(dark_lights_, "lights of zero intensity skipped");
    Note(ranged_lights_, "lights' ranges ignored (a light point's energy falls as 1 / d^2)");
    if (!model_.extensionsUsed.empty()) {
      std::vector<std::string> other;
      for (const std::string& e : model_.extensionsUsed)
        if (e != "KHR_texture_transform" && e != "KHR_lights_punctual") other.push_back(e);
      if (!other.empty())
        out_.notes.push_back(absl::StrCat("extensions ignored: ", absl::StrJoin(other, ", ")));
    }
    for (const std::string& note : material_notes_) out_.notes.push_back(note);
    return std::move(out_);
  }

 private:
  void Note(int count, const std::string& what) {
    if (count > 0) out_.notes.push_back(absl::StrCat(count, " ", what));
  }

  // alphaMode, alphaCutoff and baseColorFactor's alpha (glTF 2.0, 3.9.4 "Alpha Coverage").
  static absl::Status Alpha(const tinygltf::Material& m, const std::string& where,
                            v1::Material* material) {
    if (m.alphaMode == "MASK") {
      material->set_alpha_mode(v1::ALPHA_MODE_MASK);
    } else if (m.alphaMode == "BLEND") {
      material->set_alpha_mode(v1::ALPHA_MODE_BLEND);
    } else if (!m.alphaMode.empty() && m.alphaMode != "OPAQUE") {
      return Invalid(where + ".alphaMode",
                     absl::StrCat("'", m.alphaMode, "' is not OPAQUE, MASK or BLEND"));
    }
    if (!(m.alphaCutoff >= 0 && m.alphaCutoff <= 1))
      return Invalid(where + ".alphaCutoff", absl::StrCat(m.alphaCutoff, " is not in [0, 1]"));
    // 0 in the proto means the default 0.5; a cutoff of 0 keeps every texel, as does the
    // smallest positive float.
    material->set_alpha_cutoff(m.alphaCutoff > 0 ? static_cast<float>(m.alphaCutoff)
                                                 : std::numeric_limits<float>::min());
    const std::vector<double>& f = m.pbrMetallicRoughness.baseColorFactor;
    if (f.size() >= 4) {
      if (!(f[3] >= 0 && f[3] <= 1))
        return Invalid(where + ".pbrMetallicRoughness.baseColorFactor",
                       absl::StrCat("alpha ", f[3], " is not in [0, 1]"));
      material->set_transparency(static_cast<float>(1.0 - f[3]));
    }
    return absl::OkStatus();
  }

  absl::Status Materials() {
    int wrap = 0, other_sets = 0;
    for (size_t i = 0; i < model_.materials.size(); ++i) {
      const tinygltf::Material& m = model_.materials[i];
      const std::string where = absl::StrCat("materials[", i, "]");
      v1::Material* material = out_.scene.add_materials();
      material->set_id(absl::StrCat("material", i));
      material->set_single_sided(!m.doubleSided);
      const std::vector<double>& f = m.pbrMetallicRoughness.baseColorFactor;
      if (f.size() >= 3) {
        for (int c = 0; c < 3; ++c)
          if (!std::isfinite(f[c]))
            return Invalid(where + ".pbrMetallicRoughness.baseColorFactor", "is NaN or infinite");
        material->mutable_base_color()->set_r(static_cast<float>(f[0]));
        material->mutable_base_color()->set_g(static_cast<float>(f[1]));
        material->mutable_base_color()->set_b(static_cast<float>(f[2]));
      }
      if (auto s = Alpha(m, where, material); !s.ok()) return s;
      const tinygltf::TextureInfo& info = m.pbrMetallicRoughness.baseColorTexture;
      uv_transforms_.push_back(TextureTransformOf(info));
      if (info.index < 0) continue;
      other_sets += info.texCoord != 0;
      auto texture = Texture(info.index, where + ".pbrMetallicRoughness.baseColorTexture");
      if (!texture.ok()) return texture.status();
      material->set_texture_id(*texture);
      if (f.size() < 3) {  // glTF's default factor is white
        material->mutable_base_color()->set_r(1);
        material->mutable_base_color()->set_g(1);
        material->mutable_base_color()->set_b(1);
      }
      const int sampler = model_.textures[info.index].sampler;
      if (sampler >= 0 && sampler < static_cast<int>(model_.samplers.size())) {
        const tinygltf::Sampler& s = model_.samplers[sampler];
        wrap += s.wrapS != TINYGLTF_TEXTURE_WRAP_REPEAT || s.wrapT != TINYGLTF_TEXTURE_WRAP_REPEAT;
      }
    }
    if (wrap > 0)
      material_notes_.push_back(
          absl::StrCat(wrap, " textures with clamped or mirrored wrapping drawn repeated"));
    if (other_sets > 0)
      material_notes_.push_back(absl::StrCat(other_sets,
                                             " textures on TEXCOORD_1 or later drawn "
                                             "with TEXCOORD_0"));
    return absl::OkStatus();
  }

  // The scene texture of glTF texture `index` (its image), added once.
  absl::StatusOr<std::string> Texture(int index, const std::string& where) {
    if (index < 0 || index >= static_cast<int>(model_.textures.size()))
      return Invalid(where, absl::StrCat("texture ", index, " does not exist"));
    const int image = model_.textures[index].source;
    if (image < 0 || image >= static_cast<int>(model_.images.size()))
      return Invalid(absl::StrCat("textures[", index, "]"), "has no image");
    const std::string id = absl::StrCat("image", image);
    if (!images_added_.insert(image).second) return id;
    const tinygltf::Image& img = model_.images[image];
    v1::Texture* texture = out_.scene.add_textures();
    texture->set_id(id);
    if (!img.uri.empty() && img.uri.rfind("data:", 0) != 0) {
      texture->set_file(img.uri);  // checked to stay in the model's folder when it was read
      return id;
    }
    const std::string at = absl::StrCat("images[", image, "]");
    if (img.bufferView >= 0) {
      if (img.bufferView >= static_cast<int>(model_.bufferViews.size()))
        return Invalid(at, absl::StrCat("buffer view ", img.bufferView, " does not exist"));
      const tinygltf::BufferView& view = model_.bufferViews[img.bufferView];
      if (view.buffer < 0 || view.buffer >= static_cast<int>(model_.buffers.size()))
        return Invalid(at, "its buffer view has no buffer");
      const std::vector<unsigned char>& data = model_.buffers[view.buffer].data;
      if (view.byteOffset > data.size() || view.byteLength > data.size() - view.byteOffset ||
          view.byteLength == 0)
        return Invalid(at, absl::StrCat("buffer view ", img.bufferView, " (", view.byteOffset,
                                        " + ", view.byteLength,
                                        " bytes) is empty or goes "
                                        "beyond its buffer of ",
                                        data.size(), " bytes"));
      const auto* first = reinterpret_cast<const char*>(data.data() + view.byteOffset);
      texture->set_encoded(std::string(first, view.byteLength));
      return id;
    }
    const auto bytes = image_bytes_.find(image);
    if (bytes == image_bytes_.end() || bytes->second.empty()) return Invalid(at, "has no data");
    texture->set_encoded(std::string(bytes->second.begin(), bytes->second.end()));
    return id;
  }

  // One node: its world transform (`parent`'s times its own) into `world`, its mesh and camera.
  absl::Status Visit(int node, const Mat4& parent, Mat4& world) {
    const tinygltf::Node& n = model_.nodes[node];
    auto local = LocalTransform(n, absl::StrCat("nodes[", node, "]"));
    if (!local.ok()) return local.status();
    world = Multiply(parent, *local);
    if (n.mesh >= 0)
      if (auto s = Mesh(node, n.mesh, world); !s.ok()) return s;
    if (n.camera >= 0)
      if (auto s = Camera(node, n.camera, world); !s.ok()) return s;
    if (n.extensions.count("KHR_lights_punctual"))
      if (auto s = Light(node, world); !s.ok()) return s;
    return absl::OkStatus();
  }

  // KHR_lights_punctual: a point or spot light becomes a light point at the node's origin, its
  // intensity in candela as Aperture's; a spot's outer cone becomes its lobe's half-widths about
  // the node's -z (Aperture's lobe falls off as 1 - tan^2 / tan^2(half-width), not the
  // extension's smooth step from the inner cone). Directional lights are not light points.
  absl::Status Light(int node, const Mat4& world) {
    const std::string where = absl::StrCat("nodes[", node, "].extensions.KHR_lights_punctual");
    const tinygltf::Value& ext = model_.nodes[node].extensions.at("KHR_lights_punctual");
    if (!ext.IsObject() || !ext.Has("light") || !ext.Get("light").IsInt())
      return Invalid(where + ".light", "needs the index of a light");
    const int index = ext.Get("light").GetNumberAsInt();
    if (index < 0 || index >= static_cast<int>(model_.lights.size()))
      return Invalid(where + ".light", absl::StrCat("light ", index, " does not exist (",
                                                    model_.lights.size(), " lights)"));
    const tinygltf::Light& light = model_.lights[index];
    const std::string at = absl::StrCat("extensions.KHR_lights_punctual.lights[", index, "]");
    if (light.type == "directional") {
      ++directional_lights_;
      return absl::OkStatus();
    }
    if (light.type != "point" && light.type != "spot")
      return Invalid(at + ".type",
                     absl::StrCat("'", light.type, "' is not point, spot or directional"));
    if (!std::isfinite(light.intensity) || light.intensity < 0)
      return Invalid(at + ".intensity", "must be a finite number >= 0 (candela)");
    if (light.intensity == 0) {
      ++dark_lights_;
      return absl::OkStatus();
    }
    if (!light.color.empty() && light.color.size() != 3)
      return Invalid(at + ".color", "needs 3 numbers");
    for (double c : light.color)
      if (!std::isfinite(c) || c < 0) return Invalid(at + ".color", "must be finite and >= 0");
    if (light.range > 0) ++ranged_lights_;
    v1::LightPoint& point = *out_.scene.add_lights();
    point.mutable_position()->set_x(world[12]);
    point.mutable_position()->set_y(world[13]);
    point.mutable_position()->set_z(world[14]);
    if (light.color.size() == 3) {
      point.mutable_color()->set_r(static_cast<float>(light.color[0]));
      point.mutable_color()->set_g(static_cast<float>(light.color[1]));
      point.mutable_color()->set_b(static_cast<float>(light.color[2]));
    }
    point.set_intensity_cd(light.intensity);
    point.set_group(!light.name.empty() ? light.name : absl::StrCat("light", index));
    if (light.type == "spot") {
      const double outer = light.spot.outerConeAngle;
      if (!(outer > 0 && outer <= std::numbers::pi / 2))
        return Invalid(at + ".spot.outerConeAngle", "must be in (0, pi/2]");
      // The node's -z in the world (the third column of its transform), unit length.
      const double ax = -world[8], ay = -world[9], az = -world[10];
      const double length = std::sqrt(ax * ax + ay * ay + az * az);
      if (!(length > 0))
        return Invalid(absl::StrCat("nodes[", node, "]"), "light transform is singular");
      v1::LightLobe& lobe = *point.mutable_lobe();
      lobe.mutable_axis()->set_x(ax / length);
      lobe.mutable_axis()->set_y(ay / length);
      lobe.mutable_axis()->set_z(az / length);
      // A beam of half a right angle or wider is wider than a lobe's tangents can say: 89.9.
      const double deg = std::min(outer * 180.0 / std::numbers::pi, 89.9);
      lobe.set_horizontal_deg(deg);
      lobe.set_vertical_deg(deg);
    }
    return absl::OkStatus();
  }

  absl::Status Camera(int node, int index, const Mat4& world) {
    if (index >= static_cast<int>(model_.cameras.size()))
      return Invalid(absl::StrCat("nodes[", node, "].camera"),
                     absl::StrCat("camera ", index, " does not exist"));
    const tinygltf::Camera& c = model_.cameras[index];
    if (c.type != "perspective") {
      ++orthographic_;
      return absl::OkStatus();
    }
    GltfCamera named;
    named.name = !model_.nodes[node].name.empty() ? model_.nodes[node].name
                 : !c.name.empty()                ? c.name
                                                  : absl::StrCat("camera", index);
    v1::Camera& camera = named.camera;
    camera.mutable_position()->set_x(world[12]);
    camera.mutable_position()->set_y(world[13]);
    camera.mutable_position()->set_z(world[14]);
    double r[3][3];
    for (int col = 0; col < 3; ++col) {
      const double len =
          std::sqrt(world[col * 4] * world[col * 4] + world[col * 4 + 1] * world[col * 4 + 1] +
                    world[col * 4 + 2] * world[col * 4 + 2]);
      if (!(len > 0))
        return Invalid(absl::StrCat("nodes[", node, "]"), "camera transform is singular");
      for (int row = 0; row < 3; ++row) r[row][col] = world[col * 4 + row] / len;
    }
    SetOrientation(r, camera);
    camera.set_vertical_fov_deg(c.perspective.yfov * 180.0 / std::numbers::pi);
    if (c.perspective.znear > 0) camera.set_near(c.perspective.znear);
    if (c.perspective.zfar > 0) camera.set_far(c.perspective.zfar);
    out_.cameras.push_back(std::move(named));
    return absl::OkStatus();
  }

  absl::Status Mesh(int node, int index, const Mat4& world) {
    if (index >= static_cast<int>(model_.meshes.size()))
      return Invalid(absl::StrCat("nodes[", node, "].mesh"),
                     absl::StrCat("mesh ", index, " does not exist"));
    const tinygltf::Mesh& mesh = model_.meshes[index];
    v1::Mesh* out = out_.scene.add_meshes();
    out->set_id(absl::StrCat("node", node, "-mesh", index));
    for (size_t p = 0; p < mesh.primitives.size(); ++p)
      if (auto s = Primitive(mesh.primitives[p],
                             absl::StrCat("meshes[", index, "].primitives[", p, "]"), world, *out);
          !s.ok())
        return s;
    v1::Object* object = out_.scene.add_objects();
    object->set_mesh_id(out->id());
    return absl::OkStatus();
  }

  absl::Status Primitive(const tinygltf::Primitive& prim, const std::string& where,
                         const Mat4& world, v1::Mesh& out) {
    morph_targets_ += !prim.targets.empty();
    if (prim.mode != TINYGLTF_MODE_TRIANGLES && prim.mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
        prim.mode != TINYGLTF_MODE_TRIANGLE_FAN && prim.mode != -1) {
      ++points_or_lines_;
      return absl::OkStatus();
    }
    const auto position = prim.attributes.find("POSITION");
    if (position == prim.attributes.end()) return Invalid(where + ".attributes", "has no POSITION");
    auto positions = AccessorReader::Open(model_, position->second, where + ".attributes.POSITION");
    if (!positions.ok()) return positions.status();
    if (positions->components() != 3 || !positions->is_float())
      return Invalid(where + ".attributes.POSITION", "must be float VEC3");
    std::optional<AccessorReader> uvs;
    if (const auto uv = prim.attributes.find("TEXCOORD_0"); uv != prim.attributes.end()) {
      auto reader = AccessorReader::Open(model_, uv->second, where + ".attributes.TEXCOORD_0");
      if (!reader.ok()) return reader.status();
      if (reader->components() != 2 || reader->count() != positions->count())
        return Invalid(where + ".attributes.TEXCOORD_0",
                       "must be VEC2 with one element per position");
      uvs = *reader;
    }
    // The vertex indices, in order.
    std::vector<uint32_t> indices;
    const size_t vertex_count = positions->count();
    if (prim.indices >= 0) {
      auto reader = AccessorReader::Open(model_, prim.indices, where + ".indices");
      if (!reader.ok()) return reader.status();
      if (reader->components() != 1 || reader->is_float())
        return Invalid(where + ".indices", "must be unsigned integer SCALAR");
      indices.resize(reader->count());
      for (size_t i = 0; i < reader->count(); ++i) {
        const double v = reader->At(i, 0);
        if (!(v >= 0 && v < static_cast<double>(vertex_count)))
          return Invalid(where + ".indices",
                         absl::StrCat("index ", v, " out of range 0..",
                                      vertex_count == 0 ? 0 : vertex_count - 1));
        indices[i] = static_cast<uint32_t>(v);
      }
    } else {
      indices.resize(vertex_count);
      for (size_t i = 0; i < vertex_count; ++i) indices[i] = static_cast<uint32_t>(i);
    }
    std::vector<std::array<uint32_t, 3>> triangles;
    const int mode = prim.mode == -1 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
    if (mode == TINYGLTF_MODE_TRIANGLES) {
      for (size_t i = 0; i + 2 < indices.size(); i += 3)
        triangles.push_back({indices[i], indices[i + 1], indices[i + 2]});
    } else if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
      for (size_t i = 0; i + 2 < indices.size(); ++i)
        triangles.push_back(
            i % 2 == 0 ? std::array<uint32_t, 3>{indices[i], indices[i + 1], indices[i + 2]}
                       : std::array<uint32_t, 3>{indices[i + 1], indices[i], indices[i + 2]});
    } else {
      for (size_t i = 1; i + 1 < indices.size(); ++i)
        triangles.push_back({indices[0], indices[i], indices[i + 1]});
    }
    const int material = prim.material;
    if (material >= static_cast<int>(model_.materials.size()))
      return Invalid(where + ".material", absl::StrCat("material ", material, " does not exist"));
    const std::string material_id =
        material >= 0 ? absl::StrCat("material", material) : DefaultMaterial();
    const UvTransform* uv_map = material >= 0 ? &uv_transforms_[material] : nullptr;
    // A transform that mirrors (negative determinant) turns the winding: glTF then takes the
    // front as the other side, so the vertices are reversed to keep it counter-clockwise.
    const double det = world[0] * (world[5] * world[10] - world[9] * world[6]) -
                       world[4] * (world[1] * world[10] - world[9] * world[2]) +
                       world[8] * (world[1] * world[6] - world[5] * world[2]);
    if (det < 0)
      for (auto& t : triangles) std::swap(t[1], t[2]);
    for (const auto& t : triangles) {
      std::array<std::array<double, 3>, 3> p;
      for (int k = 0; k < 3; ++k) {
        const std::array<double, 3> local = {positions->At(t[k], 0), positions->At(t[k], 1),
                                             positions->At(t[k], 2)};
        for (double v : local)
          if (!std::isfinite(v))
            return Invalid(where + ".attributes.POSITION",
                           absl::StrCat("vertex ", t[k], " is NaN or infinite"));
        p[k] = Apply(world, local);
      }
      if (Degenerate(p)) {
        ++dropped_degenerate_;
        continue;
      }
      v1::Polygon* polygon = out.add_polygons();
      polygon->set_material_id(material_id);
      for (int k = 0; k < 3; ++k) {
        v1::Vec3* v = polygon->add_vertices();
        v->set_x(p[k][0]), v->set_y(p[k][1]), v->set_z(p[k][2]);
        if (uvs) {
          double u = uvs->At(t[k], 0), w = uvs->At(t[k], 1);
          if (!std::isfinite(u) || !std::isfinite(w))
            return Invalid(where + ".attributes.TEXCOORD_0",
                           absl::StrCat("element ", t[k], " is NaN or infinite"));
          if (uv_map != nullptr) {
            const std::array<double, 2> mapped = uv_map->Apply(u, w);
            u = mapped[0], w = mapped[1];
          }
          v1::Vec2* uv = polygon->add_uvs();
          uv->set_u(u), uv->set_v(w);
        }
      }
    }
    return absl::OkStatus();
  }

  // The scene builder's test (engine/scene/object_placement.cc): twice the area at most 1e-12 of
  // the squared extent is degenerate, and would refuse the whole scene.
  static bool Degenerate(const std::array<std::array<double, 3>, 3>& p) {
    const double ax = p[1][0] - p[0][0], ay = p[1][1] - p[0][1], az = p[1][2] - p[0][2];
    const double bx = p[2][0] - p[0][0], by = p[2][1] - p[0][1], bz = p[2][2] - p[0][2];
    const double cx = ay * bz - az * by, cy = az * bx - ax * bz, cz = ax * by - ay * bx;
    const double twice_area = std::sqrt(cx * cx + cy * cy + cz * cz);
    const double extent =
        std::max(std::sqrt(ax * ax + ay * ay + az * az), std::sqrt(bx * bx + by * by + bz * bz));
    // 1e-9 here: a thousand times the builder's margin, so that rounding between the two area
    // formulas never lets through a triangle the builder refuses.
    return !(twice_area > 1e-9 * extent * extent) || extent == 0;
  }

  std::string DefaultMaterial() {
    if (!default_material_added_) {
      v1::Material* m = out_.scene.add_materials();
      m->set_id("default");
      m->set_single_sided(true);  // the specification's default material: doubleSided false
      m->mutable_base_color()->set_r(1);
      m->mutable_base_color()->set_g(1);
      m->mutable_base_color()->set_b(1);
      default_material_added_ = true;
    }
    return "default";
  }

  const tinygltf::Model& model_;
  const std::map<int, std::vector<unsigned char>>& image_bytes_;
  const GltfImportOptions options_;
  ImportedModel out_;
  std::vector<UvTransform> uv_transforms_;  // per glTF material
  std::set<int> images_added_;
  std::vector<std::string> material_notes_;
  bool default_material_added_ = false;
  int dropped_degenerate_ = 0, morph_targets_ = 0, points_or_lines_ = 0, orthographic_ = 0;
  int directional_lights_ = 0, dark_lights_ = 0, ranged_lights_ = 0;
};

// tinygltf's file reads, kept inside the model's folder.
struct Containment {
  fs::path folder;  // weakly canonical
  std::string refused;
};

// Whether `path`, symbolic links resolved, lies under `folder` (weakly canonical).
bool IsInside(const fs::path& folder, const fs::path& path) {
  std::error_code ec;
  const fs::path resolved = fs::weakly_canonical(fs::absolute(path), ec);
  if (ec) return false;
  const auto [end, _] =
      std::mismatch(folder.begin(), folder.end(), resolved.begin(), resolved.end());
  return end == folder.end();
}

bool ReadInsideFolder(std::vector<unsigned char>* out, std::string* err, const std::string& path,
                      void* user) {
  auto* c = static_cast<Containment*>(user);
  if (!IsInside(c->folder, path)) {
    c->refused = path;
    if (err != nullptr)
      *err += absl::StrCat("'", path, "' is outside the model's folder and is not read\n");
    return false;
  }
  return tinygltf::ReadWholeFile(out, err, path, nullptr);
}

// Keeps an image's encoded bytes (tinygltf would decode them; the engine does that, within its
// limits). Not for an image in a buffer view: tinygltf 2.7 hands over the view's range without
// checking it against its buffer (the fuzz target found the over-read), so those bytes are taken
// after loading, from the checked view (Importer::Texture).
bool KeepEncodedImage(tinygltf::Image* image, const int index, std::string*, std::string*, int, int,
                      const unsigned char* bytes, int size, void* user) {
  if (image->bufferView >= 0) return true;
  auto* images = static_cast<std::map<int, std::vector<unsigned char>>*>(user);
  (*images)[index].assign(bytes, bytes + std::max(size, 0));
  return true;
}

}  // namespace

bool IsGltfPath(const std::string& path) {
  const std::string ext = absl::AsciiStrToLower(fs::path(path).extension().string());
  return ext == ".gltf" || ext == ".glb";
}

absl::StatusOr<ImportedModel> ImportGltf(const std::string& path,
                                         const GltfImportOptions& options) {
  std::ifstream in(path, std::ios::binary);
  std::error_code ec;
  if (!in || !fs::is_regular_file(path, ec))
    return absl::NotFoundError(absl::StrCat("cannot open model file '", path, "'"));
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const bool binary = absl::AsciiStrToLower(fs::path(path).extension().string()) == ".glb";
  auto imported = ImportGltfBytes(
      std::span(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size()), binary,
      fs::absolute(path).parent_path().string(), fs::path(path).stem().string(), options);
  if (!imported.ok())
    return absl::Status(imported.status().code(),
                        absl::StrCat(path, ": ", imported.status().message()));
  return imported;
}

absl::StatusOr<ImportedModel> ImportGltfBytes(std::span<const uint8_t> bytes, bool binary,
                                              const std::string& folder, const std::string& name,
                                              const GltfImportOptions& options) {
  // tinygltf takes the length as an unsigned int.
  if (bytes.size() > std::numeric_limits<unsigned int>::max())
    return absl::InvalidArgumentError("the model file is larger than 4 GiB");
  // The structure first: tinygltf passes over fields of the wrong type without a word.
  std::string_view json(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  if (binary) {
    auto chunk = GlbJsonChunk(bytes);
    if (!chunk.ok()) return chunk.status();
    json = *chunk;
  }
  if (auto s = CheckGltfJsonStructure(json); !s.ok()) return s;
  std::error_code ec;
  Containment containment;
  containment.folder = fs::weakly_canonical(fs::absolute(folder), ec);
  tinygltf::TinyGLTF loader;
  tinygltf::FsCallbacks callbacks{&tinygltf::FileExists, &tinygltf::ExpandFilePath,
                                  &ReadInsideFolder, &tinygltf::WriteWholeFile, &containment};
  loader.SetFsCallbacks(callbacks);
  std::map<int, std::vector<unsigned char>> image_bytes;
  loader.SetImageLoader(&KeepEncodedImage, &image_bytes);
  tinygltf::Model model;
  std::string err, warn;
  const std::string base_dir = containment.folder.string();
  const auto size = static_cast<unsigned int>(bytes.size());
  const bool ok =
      binary
          ? loader.LoadBinaryFromMemory(&model, &err, &warn, bytes.data(), size, base_dir)
          : loader.LoadASCIIFromString(&model, &err, &warn,
                                       reinterpret_cast<const char*>(bytes.data()), size, base_dir);
  if (!containment.refused.empty())
    return absl::InvalidArgumentError(
        absl::StrCat("'", containment.refused, "' is outside the model's folder and is not read"));
  if (!ok) {
    std::string message = err.empty() ? warn : err;
    while (!message.empty() && message.back() == '\n') message.pop_back();
    return absl::InvalidArgumentError(absl::StrCat("not a valid glTF file: ", message));
  }
  Importer importer(model, image_bytes, options);
  return importer.Run(name);
}

absl::Status ExpandModels(v1::Scene& scene, const std::string& scene_dir, bool allow_any_path,
                          std::vector<std::string>* notes, const GltfImportOptions& options) {
  if (scene.models_size() == 0) {
    for (int i = 0; i < scene.objects_size(); ++i)
      if (!scene.objects(i).model_id().empty())
        return Invalid(absl::StrCat("objects[", i, "].model_id"),
                       absl::StrCat("'", scene.objects(i).model_id(),
                                    "' is not a model of the "
                                    "scene"));
    return absl::OkStatus();
  }
  std::set<std::string> taken;
  for (const v1::Mesh& m : scene.meshes()) taken.insert(m.id());
  std::error_code ec;
  const fs::path base = scene_dir.empty() ? fs::path(".") : fs::path(scene_dir);
  const fs::path base_canonical = fs::weakly_canonical(fs::absolute(base), ec);
  uint64_t triangles = 0;                                           // of the models read so far
  std::map<std::string, std::vector<v1::LightPoint>> model_lights;  // in each model's frame
  for (int k = 0; k < scene.models_size(); ++k) {
    const v1::Model& model = scene.models(k);
    const std::string where = absl::StrCat("models[", k, "] ('", model.id(), "')");
    if (model.id().empty()) return Invalid(absl::StrCat("models[", k, "].id"), "is empty");
    if (!taken.insert(model.id()).second)
      return Invalid(where, "id is already a mesh or model of the scene");
    const fs::path file = base / model.file();
    if (!allow_any_path && !IsInside(base_canonical, file))
      return Invalid(where + ".file",
                     absl::StrCat("'", model.file(), "' is outside the scene file's folder"));
    if (!IsGltfPath(file.string()))
      return Invalid(where + ".file", absl::StrCat("'", model.file(), "' is not .gltf or .glb"));
    // Each model within the budget as it is read, and the scene's models together after.
    auto imported = ImportGltf(file.string(), options);
    if (!imported.ok())
      return absl::Status(imported.status().code(),
                          absl::StrCat(where, ": ", imported.status().message()));
    for (const v1::Mesh& part : imported->scene.meshes())
      triangles += static_cast<uint64_t>(part.polygons_size());
    if (triangles > options.max_triangles)
      return Invalid(where, absl::StrCat("the scene's models make ", triangles,
                                         " triangles with this one, above the budget of ",
                                         options.max_triangles, " triangles"));
    if (notes != nullptr)
      for (const std::string& note : imported->notes)
        notes->push_back(absl::StrCat(model.file(), ": ", note));
    const std::string prefix = model.id() + "/";
    const fs::path model_dir = fs::path(model.file()).parent_path();
    for (v1::Texture texture : imported->scene.textures()) {
      texture.set_id(prefix + texture.id());
      if (texture.source_case() == v1::Texture::kFile)
        texture.set_file((model_dir / texture.file()).lexically_normal().string());
      *scene.add_textures() = std::move(texture);
    }
    for (v1::Material material : imported->scene.materials()) {
      material.set_id(prefix + material.id());
      if (!material.texture_id().empty()) material.set_texture_id(prefix + material.texture_id());
      *scene.add_materials() = std::move(material);
    }
    for (v1::LightPoint light : imported->scene.lights()) {
      light.set_group(prefix + light.group());
      model_lights[model.id()].push_back(std::move(light));
    }
    v1::Mesh* mesh = scene.add_meshes();
    mesh->set_id(model.id());
    for (const v1::Mesh& part : imported->scene.meshes())
      for (v1::Polygon polygon : part.polygons()) {
        polygon.set_material_id(prefix + polygon.material_id());
        *mesh->add_polygons() = std::move(polygon);
      }
  }
  std::set<std::string> models, names;
  for (const v1::Model& m : scene.models()) models.insert(m.id());
  for (const v1::Object& o : scene.objects())
    if (!o.name().empty()) names.insert(o.name());
  for (int i = 0; i < scene.objects_size(); ++i) {
    v1::Object& object = *scene.mutable_objects(i);
    if (object.model_id().empty()) continue;
    const std::string where = absl::StrCat("objects[", i, "]");
    if (!object.mesh_id().empty()) return Invalid(where, "has both mesh_id and model_id");
    if (!models.count(object.model_id()))
      return Invalid(where + ".model_id",
                     absl::StrCat("'", object.model_id(), "' is not a model of the scene"));
    // The model's lights move with each object placing it: attached to it by its name (an
    // unnamed object is given one, "<model>#<index>").
    const auto lights = model_lights.find(object.model_id());
    if (lights != model_lights.end() && !lights->second.empty()) {
      if (object.name().empty()) {
        std::string name = absl::StrCat(object.model_id(), "#", i);
        while (!names.insert(name).second) name += "'";
        object.set_name(name);
      }
      for (v1::LightPoint light : lights->second) {
        light.set_object(object.name());
        *scene.add_lights() = std::move(light);
      }
    }
    object.set_mesh_id(object.model_id());
    object.clear_model_id();
  }
  scene.clear_models();
  return absl::OkStatus();
}

}  // namespace aperture
