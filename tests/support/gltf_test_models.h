// Small glTF 2.0 files written by the tests themselves (.gltf JSON, buffers as data URIs): node
// graphs that are and are not trees, a mesh placed by many nodes, structures of the wrong JSON
// type. Header only, so that the import's unit tests and the process tests share them.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace aperture::testing {

inline std::string Base64(const std::vector<uint8_t>& bytes) {
  static constexpr char kDigits[] =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (size_t i = 0; i < bytes.size(); i += 3) {
    const uint32_t n = static_cast<uint32_t>(bytes[i]) << 16 |
                       (i + 1 < bytes.size() ? static_cast<uint32_t>(bytes[i + 1]) << 8 : 0) |
                       (i + 2 < bytes.size() ? bytes[i + 2] : 0);
    out += kDigits[n >> 18 & 63];
    out += kDigits[n >> 12 & 63];
    out += i + 1 < bytes.size() ? kDigits[n >> 6 & 63] : '=';
    out += i + 2 < bytes.size() ? kDigits[n & 63] : '=';
  }
  return out;
}

inline void AppendFloat(std::vector<uint8_t>& bytes, float f) {
  uint32_t u;
  static_assert(sizeof u == sizeof f);
  __builtin_memcpy(&u, &f, sizeof u);
  for (int k = 0; k < 4; ++k) bytes.push_back(static_cast<uint8_t>(u >> (8 * k)));
}

// A model whose mesh 0 is one triangle, (0,0,0) (1,0,0) (0,1,0), unless `meshes` replaces the
// meshes, accessors, bufferViews and buffers; `nodes` and `scenes` as JSON arrays.
inline std::string GltfFile(const std::string& nodes, const std::string& scenes = "[]",
                            const std::string& meshes = "") {
  std::string geometry = meshes;
  if (geometry.empty()) {
    std::vector<uint8_t> positions;
    for (float v : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f}) AppendFloat(positions, v);
    geometry = R"("meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
      "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3"}],
      "bufferViews": [{"buffer": 0, "byteLength": 36}],
      "buffers": [{"byteLength": 36, "uri": "data:application/octet-stream;base64,)" +
               Base64(positions) + R"("}])";
  }
  std::string out = R"({"asset": {"version": "2.0"}, )";
  if (scenes != "[]") out += R"("scene": 0, "scenes": )" + scenes + ", ";
  return out + R"("nodes": )" + nodes + ", " + geometry + "}";
}

// Node i lists node i + 1 twice, `depth` levels; the last node has the triangle. Expanded as if
// it were a tree, it makes 2^depth triangles from a file of a kilobyte.
inline std::string DuplicatedChildDag(int depth) {
  std::string nodes = "[";
  for (int i = 0; i < depth; ++i)
    nodes += "{\"children\": [" + std::to_string(i + 1) + ", " + std::to_string(i + 1) + "]}, ";
  return GltfFile(nodes + "{\"mesh\": 0}]", "[{\"nodes\": [0]}]");
}

// `depth` nodes each inside the one before, each moved by -0.001 in z; the last has the triangle.
inline std::string NestedChain(int depth) {
  std::string nodes = "[";
  for (int i = 0; i < depth; ++i)
    nodes += "{\"children\": [" + std::to_string(i + 1) + "], \"translation\": [0, 0, -0.001]}, ";
  return GltfFile(nodes + "{\"mesh\": 0}]", "[{\"nodes\": [0]}]");
}

// One root with `count` children, each placing mesh 0 at x = its index.
inline std::string InstancedMesh(int count, const std::string& meshes = "") {
  std::string nodes = "[{\"children\": [";
  for (int i = 1; i <= count; ++i) nodes += (i > 1 ? ", " : "") + std::to_string(i);
  nodes += "]}";
  for (int i = 0; i < count; ++i)
    nodes += ", {\"mesh\": 0, \"translation\": [" + std::to_string(i) + ", 0, 0]}";
  return GltfFile(nodes + "]", "[{\"nodes\": [0]}]", meshes);
}

// A one-node model whose mesh's `primitives` is an object rather than an array (the shape of
// assimp-testmodels' glTF2/wrongTypes/badArray.gltf).
inline std::string PrimitivesAsObject() {
  std::string model = GltfFile(R"([{"mesh": 0}])", R"([{"nodes": [0]}])");
  model.replace(model.find("[{\"attributes\""), 1, "");
  model.replace(model.find("}}]"), 3, "}}");
  return model;
}

// Mesh 0 as a triangle strip of `triangles` triangles over 3 vertices, its indices one byte each
// (0, 1, 2, 0, 1, 2, ...): a few bytes of file per triangle.
inline std::string ByteStripMesh(int triangles) {
  std::vector<uint8_t> bytes;
  for (float v : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f}) AppendFloat(bytes, v);
  const int indices = triangles + 2;
  for (int i = 0; i < indices; ++i) bytes.push_back(static_cast<uint8_t>(i % 3));
  const std::string n = std::to_string(indices), size = std::to_string(bytes.size());
  return R"("meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "mode": 5}]}],
    "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3"},
                  {"bufferView": 1, "componentType": 5121, "count": )" +
         n + R"(, "type": "SCALAR"}],
    "bufferViews": [{"buffer": 0, "byteLength": 36},
                    {"buffer": 0, "byteOffset": 36, "byteLength": )" +
         n + R"(}],
    "buffers": [{"byteLength": )" +
         size + R"(, "uri": "data:application/octet-stream;base64,)" + Base64(bytes) + R"("}])";
}

}  // namespace aperture::testing
