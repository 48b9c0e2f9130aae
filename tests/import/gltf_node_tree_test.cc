// The glTF import's node graph (import/gltf_node_tree.h): graphs that are not trees refused
// naming the node, before anything is expanded; deep chains walked without the call stack; a
// mesh placed by several nodes still imported, once for each.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdint>
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

TEST(GltfNodeTree, AChildOfTwoParentsIsRefusedNamingIt) {
  const std::string nodes = R"([{"children": [1, 2]}, {"name": "axle", "children": [3]},
                                {"children": [3]}, {"name": "wheel", "mesh": 0}])";
  EXPECT_EQ(ErrorOf(Import(GltfFile(nodes, R"([{"nodes": [0]}])"))),
            "nodes[3] ('wheel'): listed as a child by nodes[1] ('axle') and nodes[2]; glTF nodes "
            "form a tree");
  // The same without scenes: the nodes no node lists are the roots.
  EXPECT_EQ(ErrorOf(Import(GltfFile(nodes))),
            "nodes[3] ('wheel'): listed as a child by nodes[1] ('axle') and nodes[2]; glTF nodes "
            "form a tree");
}

TEST(GltfNodeTree, AChildListedTwiceByOneParentIsRefused) {
  EXPECT_EQ(
      ErrorOf(Import(GltfFile(R"([{"children": [1, 1]}, {"mesh": 0}])", R"([{"nodes": [0]}])"))),
      "nodes[1]: listed twice as a child by nodes[0]; glTF nodes form a tree");
}

TEST(GltfNodeTree, ACycleIsRefusedNamingTheNode) {
  // 1 -> 2 -> 3 -> 1, apart from the scene's root 0 (a node of a cycle has its one parent in it).
  const std::string cycle = R"([{"mesh": 0}, {"name": "a", "children": [2]}, {"children": [3]},
                                {"children": [1]}])";
  EXPECT_EQ(ErrorOf(Import(GltfFile(cycle, R"([{"nodes": [0]}])"))),
            "nodes[1] ('a'): is its own ancestor (nodes[1] -> nodes[2] -> nodes[3] -> nodes[1], "
            "parent to child: a cycle of 3 nodes); glTF nodes form a tree");
  EXPECT_EQ(ErrorOf(Import(GltfFile(R"([{"children": [0]}])"))),
            "nodes[0]: is its own ancestor (nodes[0] -> nodes[0], parent to child: a cycle of 1 "
            "node); glTF nodes form a tree");
  // A scene's root in a cycle below itself.
  EXPECT_EQ(
      ErrorOf(Import(GltfFile(R"([{"children": [1]}, {"children": [0]}])", R"([{"nodes": [0]}])"))),
      "nodes[0]: is its own ancestor (nodes[0] -> nodes[1] -> nodes[0], parent to child: a "
      "cycle of 2 nodes); glTF nodes form a tree");
}

TEST(GltfNodeTree, ChildrenAndRootsThatDoNotExistOrAreBothAreRefused) {
  EXPECT_EQ(ErrorOf(Import(GltfFile(R"([{"name": "hub", "children": [7]}, {"mesh": 0}])",
                                    R"([{"nodes": [0]}])"))),
            "nodes[0] ('hub'): children[0] is node 7, which does not exist (nodes 0..1)");
  EXPECT_EQ(
      ErrorOf(Import(GltfFile(R"([{"children": [1]}, {"mesh": 0}])", R"([{"nodes": [0, 1]}])"))),
      "nodes[1]: a root of scenes[0] and a child of nodes[0]; glTF nodes form a tree");
  EXPECT_EQ(ErrorOf(Import(GltfFile(R"([{"mesh": 0}])", R"([{"nodes": [0, 0]}])"))),
            "nodes[0]: listed twice as a root of scenes[0]; glTF nodes form a tree");
  EXPECT_EQ(ErrorOf(Import(GltfFile(R"([{"mesh": 0}])", R"([{"nodes": [3]}])"))),
            "scenes[0].nodes[0]: node 3 does not exist (nodes 0..0)");
  // A node may be a root of several scenes.
  auto two_scenes = Import(GltfFile(R"([{"mesh": 0}])", R"([{"nodes": [0]}, {"nodes": [0]}])"));
  ASSERT_TRUE(two_scenes.ok()) << two_scenes.status();
  EXPECT_EQ(Triangles(*two_scenes), 1u);
}

// 40 levels of a node listing its child twice: 2^40 triangles if it were expanded. Refused at
// once, before anything is expanded.
TEST(GltfNodeTree, TheDuplicatedChildDagOfDepth40IsRefusedAtOnce) {
  const std::string file = testing::DuplicatedChildDag(40);
  EXPECT_LT(file.size(), 2000u);
  const auto start = std::chrono::steady_clock::now();
  const std::string error = ErrorOf(Import(file));
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_EQ(error, "nodes[40]: listed twice as a child by nodes[39]; glTF nodes form a tree");
  EXPECT_LT(seconds, 1.0);  // a millisecond or so; expanding 2^40 triangles takes forever
}

// 100,000 nested nodes: walked on explicit stacks (a recursive walk would overflow the call
// stack near 20,000 levels), each level's transform applied.
TEST(GltfNodeTree, ADeepChainIsImported) {
  constexpr int kDepth = 100'000;
  auto imported = Import(testing::NestedChain(kDepth));
  ASSERT_TRUE(imported.ok()) << imported.status();
  ASSERT_EQ(Triangles(*imported), 1u);
  const v1::Polygon& triangle = imported->scene.meshes(0).polygons(0);
  EXPECT_NEAR(triangle.vertices(0).z(), -0.001 * kDepth, 1e-6);
  EXPECT_EQ(triangle.vertices(1).x(), 1.0);
}

TEST(GltfNodeTree, AMeshPlacedBySeveralNodesIsImportedOnceForEach) {
  auto imported = Import(testing::InstancedMesh(3));
  ASSERT_TRUE(imported.ok()) << imported.status();
  ASSERT_EQ(imported->scene.meshes_size(), 3);
  ASSERT_EQ(imported->scene.objects_size(), 3);
  for (int i = 0; i < 3; ++i) {
    ASSERT_EQ(imported->scene.meshes(i).polygons_size(), 1);
    EXPECT_EQ(imported->scene.meshes(i).polygons(0).vertices(0).x(), i);  // its node's place
  }
}

}  // namespace
}  // namespace aperture
