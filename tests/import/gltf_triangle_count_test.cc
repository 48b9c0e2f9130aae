// The glTF import's triangle budget (import/gltf_triangle_count.h): a model's triangles, each mesh
// once for every node that places it, counted from the accessors' counts against
// GltfImportOptions::max_triangles before any polygon is made; counts beyond their buffers refused
// when they are counted; a scene file's models sharing the budget.
#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <span>
#include <string>

#include "gltf_import.h"
#include "support/gltf_import_helpers.h"
#include "support/gltf_test_models.h"

namespace aperture {
namespace {

using testing::GltfFile;

using testing::ErrorOf;
using testing::Triangles;

absl::StatusOr<ImportedModel> Import(const std::string& json,
                                     const GltfImportOptions& options = {}) {
  return testing::ImportJson(json, options);
}

TEST(GltfTriangleBudget, TheCountIsCheckedAgainstTheBudget) {
  GltfImportOptions options;
  options.max_triangles = 3;
  auto exact = Import(testing::InstancedMesh(3), options);
  ASSERT_TRUE(exact.ok()) << exact.status();
  EXPECT_EQ(Triangles(*exact), 3u);
  EXPECT_EQ(ErrorOf(Import(testing::InstancedMesh(4), options)),
            "the model's nodes place 4 triangles (a mesh counted once for each node that places "
            "it), above the budget of 3 triangles per model");
}

// 20,000 nodes placing a strip of 100,000 triangles (a byte of file each): 2 * 10^9 triangles,
// hundreds of gigabytes as polygons. Refused from the counts alone, before any is made.
TEST(GltfTriangleBudget, ManyNodesPlacingOneMeshAreRefusedBeforeAllocation) {
  const std::string file = testing::InstancedMesh(20'000, testing::ByteStripMesh(100'000));
  EXPECT_LT(file.size(), 2'000'000u);
  const auto start = std::chrono::steady_clock::now();
  const std::string error = ErrorOf(Import(file));
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_EQ(error,
            "the model's nodes place 2000000000 triangles (a mesh counted once for each "
            "node that places it), above the budget of " +
                std::to_string(kDefaultGltfMaxTriangles) + " triangles per model");
  EXPECT_LT(seconds, 5.0);  // parsing the file; making even one instance's polygons takes longer
  // One instance of it fits the default budget and is made, strip and all.
  auto one = Import(testing::InstancedMesh(1, testing::ByteStripMesh(100'000)));
  ASSERT_TRUE(one.ok()) << one.status();
  EXPECT_EQ(Triangles(*one), 100'000u);
}

// An accessor that claims 2^31 elements of a 36-byte buffer is refused when it is counted, not
// read into a vector of that size.
TEST(GltfTriangleBudget, AnAccessorCountBeyondItsBufferIsRefused) {
  std::string file = testing::GltfFile(R"([{"mesh": 0}])", R"([{"nodes": [0]}])");
  const std::string count = "\"count\": 3";
  file.replace(file.find(count), count.size(), "\"count\": 2147483648");
  EXPECT_EQ(ErrorOf(Import(file)),
            "meshes[0].primitives[0].attributes.POSITION (accessors[0]): 2147483648 elements from "
            "byte 0 go beyond buffer view 0 of 36 bytes");
}

// A scene file's models share the budget: each is counted as it is read, and the one that takes
// the scene's models past it is named.
TEST(GltfTriangleBudget, ASceneFilesModelsShareTheBudget) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() /
                                    ("aperture_gltf_budget_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "a.gltf") << testing::InstancedMesh(2);
  std::ofstream(dir / "b.gltf") << testing::InstancedMesh(2);
  v1::Scene scene;
  for (const char* id : {"a", "b"}) {
    v1::Model* model = scene.add_models();
    model->set_id(id);
    model->set_file(std::string(id) + ".gltf");
  }
  GltfImportOptions options;
  options.max_triangles = 4;
  v1::Scene fits = scene;
  EXPECT_TRUE(ExpandModels(fits, dir.string(), false, nullptr, options).ok());
  options.max_triangles = 3;
  const absl::Status over = ExpandModels(scene, dir.string(), false, nullptr, options);
  std::filesystem::remove_all(dir);
  EXPECT_EQ(over.message(),
            "models[1] ('b'): the scene's models make 4 triangles with this one, above the budget "
            "of 3 triangles");
}

}  // namespace
}  // namespace aperture
