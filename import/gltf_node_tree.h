// The node hierarchy of a glTF model, checked to be what glTF 2.0 requires ("3.5.3
// Transformations": the nodes form disjoint strict trees, a node has at most one parent, a scene's
// roots are no node's children) before anything walks it. A graph that shares a child between
// parents expands exponentially with its depth (each level doubles the nodes below it), and a cycle
// never ends, so both are refused with the node named; the check and the walks it offers use
// explicit stacks, so a chain of any depth costs memory, not the call stack.
#pragma once

#include <tiny_gltf.h>

#include <span>
#include <string>
#include <vector>

#include "absl/status/statusor.h"

namespace aperture {

class NodeTree {
 public:
  // Every node and every scene of `model` (also those the import does not draw): children and
  // roots that exist, at most one parent per node, listed once, no cycle, no scene root that is
  // a child. Errors name the node: "nodes[3] ('wheel'): listed as a child by nodes[1] and
  // nodes[2]; glTF nodes form a tree".
  static absl::StatusOr<NodeTree> Check(const tinygltf::Model& model);

  // The node's parent, -1 for a node that no node lists as a child.
  int parent(int node) const { return parent_[node]; }
  // The nodes that no node lists as a child, in the file's order.
  std::vector<int> Roots() const;
  // `roots` and every node below them, each after its parent, depth first in the file's order of
  // children (the order a recursive walk would take). `roots` must be nodes without a parent.
  std::vector<int> DepthFirst(std::span<const int> roots) const;

 private:
  NodeTree(const tinygltf::Model& model, std::vector<int> parent)
      : model_(&model), parent_(std::move(parent)) {}
  const tinygltf::Model* model_;
  std::vector<int> parent_;
};

// "nodes[3] ('wheel')", or "nodes[3]" for a node without a name: how errors name a node.
std::string NodeName(const tinygltf::Model& model, int node);

}  // namespace aperture
