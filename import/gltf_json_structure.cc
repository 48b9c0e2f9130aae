#include "gltf_json_structure.h"

#include <climits>
#include <cstring>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "absl/strings/str_cat.h"

namespace aperture {
namespace {

using Json = nlohmann::json;

// Where a value is in the file, as a chain of frames on the checker's stack: rendered
// ("meshes[0].primitives") only for an error.
struct JsonPath {
  const JsonPath* parent = nullptr;
  const char* key = nullptr;  // a member's name; nullptr: an array element
  size_t index = 0;

  std::string ToString() const {
    if (parent == nullptr) return "";  // the document
    std::string head = parent->ToString();
    if (key == nullptr) return absl::StrCat(head, "[", index, "]");
    return head.empty() ? std::string(key) : absl::StrCat(head, ".", key);
  }
};

// Whether `value` has arrays or objects nested deeper than `limit` levels, itself level 1; on an
// explicit stack, whatever the depth.
bool NestsDeeperThan(const Json& value, int limit) {
  std::vector<std::pair<const Json*, int>> pending;
  if (value.is_structured()) pending.push_back({&value, 1});
  while (!pending.empty()) {
    const auto [v, level] = pending.back();
    pending.pop_back();
    if (level > limit) return true;
    for (const Json& child : *v)
      if (child.is_structured()) pending.push_back({&child, level + 1});
  }
  return false;
}

bool IsIndex(const Json& v) {  // glTF's glTFid, as tinygltf stores it: an int
  return v.is_number_unsigned() && v.get<uint64_t>() <= static_cast<uint64_t>(INT_MAX);
}

// The fields of the glTF schema that the importer reads (import/gltf_import.cc), each checked for
// its JSON type; the first error is kept and the rest skipped.
class StructureCheck {
 public:
  absl::Status Run(const Json& doc) {
    if (!doc.is_object()) return absl::InvalidArgumentError("the JSON is not an object");
    const JsonPath root;
    Index(doc, "scene", root);
    Elements(doc, "scenes", root, [&](const Json& scene, const JsonPath& at) {
      Name(scene, at);
      IndexArray(scene, "nodes", at);
    });
    Elements(doc, "nodes", root, [&](const Json& node, const JsonPath& at) {
      Name(node, at);
      IndexArray(node, "children", at);
      Index(node, "mesh", at);
      Index(node, "camera", at);
      Index(node, "skin", at);
      Numbers(node, "matrix", at, 16);
      Numbers(node, "rotation", at, 4);
      Numbers(node, "scale", at, 3);
      Numbers(node, "translation", at, 3);
    });
    Elements(doc, "meshes", root, [&](const Json& mesh, const JsonPath& at) {
      Name(mesh, at);
      Elements(
          mesh, "primitives", at,
          [&](const Json& primitive, const JsonPath& p) {
            Object(
                primitive, "attributes", p,
                [&](const Json& attributes, const JsonPath& a) {
                  for (const auto& [semantic, accessor] : attributes.items())
                    if (!IsIndex(accessor)) {
                      const std::string name = semantic;
                      const JsonPath member{&a, name.c_str()};
                      Fail(member, "expected an accessor index (an integer from 0 to 2147483647)");
                      return;
                    }
                },
                kRequired);
            Index(primitive, "indices", p);
            Index(primitive, "material", p);
            Integer(primitive, "mode", p, 0, 6);
            Elements(primitive, "targets", p, [](const Json&, const JsonPath&) {});
          },
          kRequired);
    });
    Elements(doc, "accessors", root, [&](const Json& accessor, const JsonPath& at) {
      Name(accessor, at);
      Index(accessor, "bufferView", at);
      Unsigned(accessor, "byteOffset", at);
      Integer(accessor, "componentType", at, 0, INT_MAX, kRequired);
      Bool(accessor, "normalized", at);
      Integer(accessor, "count", at, 1, UINT64_MAX, kRequired);
      String(accessor, "type", at, kRequired);
      Object(accessor, "sparse", at, [](const Json&, const JsonPath&) {});
    });
    Elements(doc, "bufferViews", root, [&](const Json& view, const JsonPath& at) {
      Name(view, at);
      Index(view, "buffer", at, kRequired);
      Unsigned(view, "byteOffset", at);
      Integer(view, "byteLength", at, 1, UINT64_MAX, kRequired);
      Integer(view, "byteStride", at, 4, 252);
    });
    Elements(doc, "buffers", root, [&](const Json& buffer, const JsonPath& at) {
      Name(buffer, at);
      String(buffer, "uri", at);
      Integer(buffer, "byteLength", at, 1, UINT64_MAX, kRequired);
    });
    Elements(doc, "materials", root, [&](const Json& material, const JsonPath& at) {
      Name(material, at);
      Object(material, "pbrMetallicRoughness", at, [&](const Json& pbr, const JsonPath& p) {
        Numbers(pbr, "baseColorFactor", p, 4);
        Object(pbr, "baseColorTexture", p, [&](const Json& info, const JsonPath& t) {
          Index(info, "index", t, kRequired);
          Unsigned(info, "texCoord", t);
          Object(info, "extensions", t, [&](const Json& extensions, const JsonPath& e) {
            Object(extensions, "KHR_texture_transform", e, [&](const Json& k, const JsonPath& x) {
              Numbers(k, "offset", x, 2);
              Number(k, "rotation", x);
              Numbers(k, "scale", x, 2);
              Unsigned(k, "texCoord", x);
            });
          });
        });
      });
      String(material, "alphaMode", at);
      Number(material, "alphaCutoff", at);
      Bool(material, "doubleSided", at);
    });
    Elements(doc, "textures", root, [&](const Json& texture, const JsonPath& at) {
      Name(texture, at);
      Index(texture, "source", at);
      Index(texture, "sampler", at);
    });
    Elements(doc, "samplers", root, [&](const Json& sampler, const JsonPath& at) {
      Name(sampler, at);
      Integer(sampler, "wrapS", at, 0, INT_MAX);
      Integer(sampler, "wrapT", at, 0, INT_MAX);
    });
    Elements(doc, "images", root, [&](const Json& image, const JsonPath& at) {
      Name(image, at);
      String(image, "uri", at);
      Index(image, "bufferView", at);
      String(image, "mimeType", at);
    });
    Elements(doc, "cameras", root, [&](const Json& camera, const JsonPath& at) {
      Name(camera, at);
      String(camera, "type", at, kRequired);
      Object(camera, "perspective", at, [&](const Json& perspective, const JsonPath& p) {
        Number(perspective, "yfov", p, kRequired);
        Number(perspective, "znear", p, kRequired);
        Number(perspective, "zfar", p);
        Number(perspective, "aspectRatio", p);
      });
    });
    Elements(doc, "skins", root, [](const Json&, const JsonPath&) {});
    Elements(doc, "animations", root, [](const Json&, const JsonPath&) {});
    StringArray(doc, "extensionsUsed", root);
    return status_;
  }

 private:
  enum Need { kOptional, kRequired };

  void Fail(const JsonPath& at, const std::string& what) {
    if (status_.ok()) status_ = absl::InvalidArgumentError(absl::StrCat(at.ToString(), ": ", what));
  }

  // The member `key` of `object`, or nullptr when it is absent (an error when it is required) or
  // an earlier field failed.
  const Json* Member(const Json& object, const char* key, const JsonPath& at, Need need) {
    if (!status_.ok()) return nullptr;
    const auto it = object.find(key);
    if (it != object.end()) return &*it;
    if (need == kRequired) Fail(JsonPath{&at, key}, "is missing");
    return nullptr;
  }

  // An array of objects, `each` called on every element.
  template <class Each>
  void Elements(const Json& object, const char* key, const JsonPath& at, Each&& each,
                Need need = kOptional) {
    const Json* v = Member(object, key, at, need);
    if (v == nullptr) return;
    const JsonPath path{&at, key};
    if (!v->is_array()) return Fail(path, "expected an array");
    for (size_t i = 0; i < v->size() && status_.ok(); ++i) {
      const JsonPath element{&path, nullptr, i};
      if (!(*v)[i].is_object()) return Fail(element, "expected an object");
      each((*v)[i], element);
    }
  }

  template <class Inside>
  void Object(const Json& object, const char* key, const JsonPath& at, Inside&& inside,
              Need need = kOptional) {
    const Json* v = Member(object, key, at, need);
    if (v == nullptr) return;
    const JsonPath path{&at, key};
    if (!v->is_object()) return Fail(path, "expected an object");
    inside(*v, path);
  }

  void Index(const Json& object, const char* key, const JsonPath& at, Need need = kOptional) {
    const Json* v = Member(object, key, at, need);
    if (v != nullptr && !IsIndex(*v))
      Fail(JsonPath{&at, key}, "expected an index (an integer from 0 to 2147483647)");
  }

  void IndexArray(const Json& object, const char* key, const JsonPath& at) {
    const Json* v = Member(object, key, at, kOptional);
    if (v == nullptr) return;
    const JsonPath path{&at, key};
    if (!v->is_array()) return Fail(path, "expected an array");
    for (size_t i = 0; i < v->size(); ++i)
      if (!IsIndex((*v)[i]))
        return Fail(JsonPath{&path, nullptr, i},
                    "expected an index (an integer from 0 to 2147483647)");
  }

  // Every integer the importer reads is non-negative.
  void Integer(const Json& object, const char* key, const JsonPath& at, uint64_t min, uint64_t max,
               Need need = kOptional) {
    const Json* v = Member(object, key, at, need);
    if (v == nullptr) return;
    if (!v->is_number_unsigned() || v->get<uint64_t>() < min || v->get<uint64_t>() > max)
      Fail(JsonPath{&at, key}, max == UINT64_MAX
                                   ? absl::StrCat("expected an integer of at least ", min)
                                   : absl::StrCat("expected an integer from ", min, " to ", max));
  }

  void Unsigned(const Json& object, const char* key, const JsonPath& at) {
    const Json* v = Member(object, key, at, kOptional);
    if (v != nullptr && !v->is_number_unsigned())
      Fail(JsonPath{&at, key}, "expected a non-negative integer");
  }

  void Number(const Json& object, const char* key, const JsonPath& at, Need need = kOptional) {
    const Json* v = Member(object, key, at, need);
    if (v != nullptr && !v->is_number()) Fail(JsonPath{&at, key}, "expected a number");
  }

  // An array of exactly `count` numbers.
  void Numbers(const Json& object, const char* key, const JsonPath& at, size_t count) {
    const Json* v = Member(object, key, at, kOptional);
    if (v == nullptr) return;
    bool numbers = v->is_array() && v->size() == count;
    for (size_t i = 0; numbers && i < count; ++i) numbers = (*v)[i].is_number();
    if (!numbers)
      Fail(JsonPath{&at, key}, absl::StrCat("expected an array of ", count, " numbers"));
  }

  void String(const Json& object, const char* key, const JsonPath& at, Need need = kOptional) {
    const Json* v = Member(object, key, at, need);
    if (v != nullptr && !v->is_string()) Fail(JsonPath{&at, key}, "expected a string");
  }

  void StringArray(const Json& object, const char* key, const JsonPath& at) {
    const Json* v = Member(object, key, at, kOptional);
    if (v == nullptr) return;
    const JsonPath path{&at, key};
    if (!v->is_array()) return Fail(path, "expected an array");
    for (size_t i = 0; i < v->size(); ++i)
      if (!(*v)[i].is_string()) return Fail(JsonPath{&path, nullptr, i}, "expected a string");
  }

  void Bool(const Json& object, const char* key, const JsonPath& at) {
    const Json* v = Member(object, key, at, kOptional);
    if (v != nullptr && !v->is_boolean()) Fail(JsonPath{&at, key}, "expected true or false");
  }

  void Name(const Json& object, const JsonPath& at) { String(object, "name", at); }

  absl::Status status_;
};

// Where the document nests too deep: the top-level member, or its array's element.
std::string TooDeep(const Json& doc) {
  for (const auto& [key, value] : doc.items()) {
    if (!NestsDeeperThan(value, kMaxGltfJsonNesting - 1)) continue;
    if (value.is_array())
      for (size_t i = 0; i < value.size(); ++i)
        if (NestsDeeperThan(value[i], kMaxGltfJsonNesting - 2))
          return absl::StrCat(key, "[", i, "]");
    return key;
  }
  return "the document";
}

uint32_t ReadU32(const uint8_t* p) {  // glTF's binary form is little-endian
  return static_cast<uint32_t>(p[0]) | static_cast<uint32_t>(p[1]) << 8 |
         static_cast<uint32_t>(p[2]) << 16 | static_cast<uint32_t>(p[3]) << 24;
}

}  // namespace

absl::Status CheckGltfJsonStructure(std::string_view json) {
  Json doc;
  try {
    doc = Json::parse(json.begin(), json.end());
  } catch (const Json::exception& e) {
    return absl::InvalidArgumentError(absl::StrCat("not a valid glTF file: ", e.what()));
  }
  if (NestsDeeperThan(doc, kMaxGltfJsonNesting))
    return absl::InvalidArgumentError(absl::StrCat(
        TooDeep(doc), ": arrays and objects nested deeper than ", kMaxGltfJsonNesting, " levels"));
  return StructureCheck().Run(doc);
}

absl::StatusOr<std::string_view> GlbJsonChunk(std::span<const uint8_t> bytes) {
  constexpr uint32_t kJsonChunk = 0x4E4F534A;  // "JSON"
  if (bytes.size() < 20 || std::memcmp(bytes.data(), "glTF", 4) != 0)
    return absl::InvalidArgumentError("not a valid glTF file: no .glb header");
  const uint32_t length = ReadU32(bytes.data() + 12), type = ReadU32(bytes.data() + 16);
  if (type != kJsonChunk)
    return absl::InvalidArgumentError("not a valid glTF file: the .glb's first chunk is not JSON");
  if (length > bytes.size() - 20)
    return absl::InvalidArgumentError(
        absl::StrCat("not a valid glTF file: the .glb's JSON chunk of ", length,
                     " bytes goes beyond the file of ", bytes.size(), " bytes"));
  return std::string_view(reinterpret_cast<const char*>(bytes.data()) + 20, length);
}

}  // namespace aperture
