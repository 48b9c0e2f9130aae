// The glTF file's JSON structure (import/gltf_json_structure.h): a field the importer reads with
// the wrong JSON type is refused naming its path, where tinygltf alone passes over it (a
// `primitives` object imported as an empty model); nesting is bounded; a .glb's JSON chunk must
// lie within the file.
#include "gltf_json_structure.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "gltf_import.h"
#include "support/gltf_test_models.h"

namespace aperture {
namespace {

absl::StatusOr<ImportedModel> Import(const std::string& bytes, bool binary = false) {
  return ImportGltfBytes(std::span(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size()),
                         binary, "/nonexistent", "test");
}

// The one-triangle model with a material, `from` replaced by `to`.
std::string Edited(const std::string& from, const std::string& to) {
  std::string file = testing::GltfFile(R"([{"name": "tri", "mesh": 0}])", R"([{"nodes": [0]}])");
  const std::string material = R"("materials": [{"pbrMetallicRoughness": {"baseColorFactor":
      [1, 1, 1, 1]}}], )";
  file.insert(file.find("\"meshes\""), material);
  file.replace(file.find(R"("attributes": {"POSITION": 0}})"),
               std::string(R"("attributes": {"POSITION": 0}})").size(),
               R"("attributes": {"POSITION": 0}, "material": 0})");
  if (from.empty()) return file;
  const size_t at = file.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) file.replace(at, from.size(), to);
  return file;
}

TEST(GltfJsonStructure, TheUneditedModelImports) {
  auto imported = Import(Edited("", ""));
  ASSERT_TRUE(imported.ok()) << imported.status();
  ASSERT_EQ(imported->scene.meshes_size(), 1);
  EXPECT_EQ(imported->scene.meshes(0).polygons_size(), 1);
}

struct WrongType {
  const char* from;
  const char* to;
  const char* error;
};

TEST(GltfJsonStructure, FieldsOfTheWrongTypeAreRefusedNamingTheirPath) {
  const WrongType cases[] = {
      // assimp-testmodels' glTF2/wrongTypes/badArray.gltf
      {R"("primitives": [{"attributes": {"POSITION": 0}, "material": 0}])",
       R"("primitives": {"not an array": {"POSITION": 0}, "material": 0})",
       "meshes[0].primitives: expected an array"},
      {R"("primitives": [{"attributes": {"POSITION": 0}, "material": 0}])", R"("primitives": [7])",
       "meshes[0].primitives[0]: expected an object"},
      {R"("attributes": {"POSITION": 0}, )", "", "meshes[0].primitives[0].attributes: is missing"},
      {R"("POSITION": 0)", R"("POSITION": "0")",
       "meshes[0].primitives[0].attributes.POSITION: expected an accessor index (an integer from "
       "0 to 2147483647)"},
      // badObject.gltf
      {R"("pbrMetallicRoughness": {"baseColorFactor":
      [1, 1, 1, 1]})",
       R"("pbrMetallicRoughness": ["not an object"])",
       "materials[0].pbrMetallicRoughness: expected an object"},
      {"[1, 1, 1, 1]", "[1, 1, 1]",
       "materials[0].pbrMetallicRoughness.baseColorFactor: expected an array of 4 numbers"},
      // badUint.gltf
      {"[1, 1, 1, 1]}", R"([1, 1, 1, 1], "baseColorTexture": {"index": -1}})",
       "materials[0].pbrMetallicRoughness.baseColorTexture.index: expected an index (an integer "
       "from 0 to 2147483647)"},
      // badExtension.gltf
      {"[1, 1, 1, 1]}",
       R"([1, 1, 1, 1], "baseColorTexture": {"index": 0, "extensions":
          {"KHR_texture_transform": "Not an object"}}})",
       "materials[0].pbrMetallicRoughness.baseColorTexture.extensions.KHR_texture_transform: "
       "expected an object"},
      // badString.gltf
      {R"("name": "tri")", R"("name": 42)", "nodes[0].name: expected a string"},
      // tinygltf would cast it to int: node 0's mesh 0
      {R"("mesh": 0)", R"("mesh": 4294967296)",
       "nodes[0].mesh: expected an index (an integer from 0 to 2147483647)"},
      {R"("mesh": 0)", R"("mesh": 0, "children": [1, "2"])",
       "nodes[0].children[1]: expected an index (an integer from 0 to 2147483647)"},
      {R"("mesh": 0)", R"("mesh": 0, "matrix": [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0])",
       "nodes[0].matrix: expected an array of 16 numbers"},
      {R"("nodes": [0])", R"("nodes": {"0": 0})", "scenes[0].nodes: expected an array"},
      {R"("count": 3)", R"("count": 0)", "accessors[0].count: expected an integer of at least 1"},
      {R"("byteLength": 36})", R"("byteLength": 36, "byteStride": 2})",
       "bufferViews[0].byteStride: expected an integer from 4 to 252"},
      {R"("type": "VEC3")", R"("type": 3)", "accessors[0].type: expected a string"},
      {R"("meshes": [)", R"("extensionsUsed": [1], "meshes": [)",
       "extensionsUsed[0]: expected a string"},
  };
  for (const WrongType& c : cases) {
    SCOPED_TRACE(c.to);
    auto imported = Import(Edited(c.from, c.to));
    ASSERT_FALSE(imported.ok());
    EXPECT_EQ(imported.status().code(), absl::StatusCode::kInvalidArgument);
    EXPECT_EQ(std::string(imported.status().message()), c.error);
  }
}

TEST(GltfJsonStructure, TheDefaultSceneMustExist) {
  auto imported = Import(Edited(R"("scene": 0)", R"("scene": 3)"));
  ASSERT_FALSE(imported.ok());
  EXPECT_EQ(imported.status().message(), "scene: scene 3 does not exist (1 scenes)");
}

// tinygltf turns `extras` into its own values recursively, which 100,000 levels would overflow
// the stack with.
TEST(GltfJsonStructure, NestingIsBoundedNamingWhereItIsTooDeep) {
  auto nested = [](int levels) { return std::string(levels, '[') + std::string(levels, ']'); };
  // The document is level 1.
  const std::string top = R"("asset": {)";
  auto fits = Import(Edited(top, "\"extras\": " + nested(kMaxGltfJsonNesting - 1) + ", " + top));
  EXPECT_TRUE(fits.ok()) << fits.status();
  auto deep = Import(Edited(top, "\"extras\": " + nested(kMaxGltfJsonNesting) + ", " + top));
  ASSERT_FALSE(deep.ok());
  EXPECT_EQ(deep.status().message(), "extras[0]: arrays and objects nested deeper than 64 levels");
  auto deeper = Import(Edited(R"("name": "tri")", "\"extras\": " + nested(100'000)));
  ASSERT_FALSE(deeper.ok());
  EXPECT_EQ(deeper.status().message(), "nodes[0]: arrays and objects nested deeper than 64 levels");
}

TEST(GltfJsonStructure, JsonThatDoesNotParseIsRefused) {
  auto imported = Import(Edited(R"("asset")", "asset"));
  ASSERT_FALSE(imported.ok());
  EXPECT_EQ(imported.status().message().rfind("not a valid glTF file: ", 0), 0u)
      << imported.status();
}

std::string Glb(const std::string& json, uint32_t declared_length) {
  std::string out = "glTF";
  auto u32 = [&](uint32_t v) {
    for (int k = 0; k < 4; ++k) out += static_cast<char>(v >> (8 * k) & 0xff);
  };
  u32(2);
  u32(static_cast<uint32_t>(20 + json.size()));
  u32(declared_length);
  u32(0x4E4F534A);  // "JSON"
  return out + json;
}

TEST(GltfJsonStructure, TheGlbJsonChunkIsCheckedToo) {
  std::string json = Edited(R"("primitives": [{"attributes": {"POSITION": 0}, "material": 0}])",
                            R"("primitives": {"attributes": {"POSITION": 0}})");
  json.append((4 - json.size() % 4) % 4, ' ');
  auto wrong = Import(Glb(json, static_cast<uint32_t>(json.size())), /*binary=*/true);
  ASSERT_FALSE(wrong.ok());
  EXPECT_EQ(wrong.status().message(), "meshes[0].primitives: expected an array");
  auto beyond = Import(Glb(json, 1'000'000), /*binary=*/true);
  ASSERT_FALSE(beyond.ok());
  EXPECT_EQ(beyond.status().message(),
            "not a valid glTF file: the .glb's JSON chunk of 1000000 bytes goes beyond the file "
            "of " +
                std::to_string(20 + json.size()) + " bytes");
}

}  // namespace
}  // namespace aperture
