#include "gltf_node_tree.h"

#include <algorithm>
#include <cstdint>

#include "absl/strings/str_cat.h"

namespace aperture {
namespace {

constexpr char kTree[] = "; glTF nodes form a tree";
constexpr size_t kNameShown = 60;  // characters of a node's name an error quotes
constexpr size_t kCycleShown = 8;  // nodes of a cycle an error lists

// A node's state in the depth-first check.
enum class Mark : uint8_t { kUnseen, kOpen, kDone };  // kOpen: on the current path from a root

// Who put a node in the tree: its parent (>= 0), a scene (kSceneRoot, the scene in root_of), or
// nobody yet (kNoParent: reached by the sweep over nodes that no scene reaches).
constexpr int kNoParent = -1;
constexpr int kSceneRoot = -2;

absl::Status Refuse(std::string what) { return absl::InvalidArgumentError(std::move(what)); }

class TreeCheck {
 public:
  explicit TreeCheck(const tinygltf::Model& model)
      : model_(model),
        count_(static_cast<int>(model.nodes.size())),
        mark_(model.nodes.size(), Mark::kUnseen),
        parent_(model.nodes.size(), kNoParent),
        root_of_(model.nodes.size(), -1) {}

  absl::StatusOr<std::vector<int>> Run() {
    // The scenes' roots first, so that an error in what is drawn is the one reported.
    for (size_t s = 0; s < model_.scenes.size(); ++s) {
      const std::vector<int>& roots = model_.scenes[s].nodes;
      for (size_t k = 0; k < roots.size(); ++k) {
        const int root = roots[k];
        if (root < 0 || root >= count_)
          return Refuse(absl::StrCat("scenes[", s, "].nodes[", k, "]: node ", root,
                                     " does not exist (", Existing(), ")"));
        if (mark_[root] == Mark::kDone) {
          if (parent_[root] >= 0) return RootAndChild(root, static_cast<int>(s));
          if (root_of_[root] == static_cast<int>(s))
            return Refuse(absl::StrCat(NodeName(model_, root),
                                       ": listed twice as a root of scenes[", s, "]", kTree));
          continue;  // a root of an earlier scene as well: glTF allows that
        }
        parent_[root] = kSceneRoot;
        root_of_[root] = static_cast<int>(s);
        if (auto status = Walk(root); !status.ok()) return status;
      }
    }
    // Then every node no scene reaches: a cycle is never below a root.
    for (int n = 0; n < count_; ++n)
      if (mark_[n] == Mark::kUnseen)
        if (auto status = Walk(n); !status.ok()) return status;
    for (int& p : parent_) p = std::max(p, kNoParent);
    return std::move(parent_);
  }

 private:
  struct Frame {
    int node;
    size_t next_child;
  };

  // Depth first from `start`, on an explicit stack: every child is checked when its parent
  // lists it.
  absl::Status Walk(int start) {
    std::vector<Frame> path = {{start, 0}};
    mark_[start] = Mark::kOpen;
    while (!path.empty()) {
      Frame& top = path.back();
      const std::vector<int>& children = model_.nodes[top.node].children;
      if (top.next_child == children.size()) {
        mark_[top.node] = Mark::kDone;
        path.pop_back();
        continue;
      }
      const size_t k = top.next_child++;
      const int parent = top.node, child = children[k];
      if (child < 0 || child >= count_)
        return Refuse(absl::StrCat(NodeName(model_, parent), ": children[", k, "] is node ", child,
                                   ", which does not exist (", Existing(), ")"));
      switch (mark_[child]) {
        case Mark::kOpen:
          return Cycle(path, child);
        case Mark::kDone:
          if (parent_[child] == kSceneRoot) return RootAndChild(child, root_of_[child], parent);
          if (parent_[child] == parent)
            return Refuse(absl::StrCat(NodeName(model_, child), ": listed twice as a child by ",
                                       NodeName(model_, parent), kTree));
          if (parent_[child] >= 0)
            return Refuse(absl::StrCat(NodeName(model_, child), ": listed as a child by ",
                                       NodeName(model_, parent_[child]), " and ",
                                       NodeName(model_, parent), kTree));
          // Reached before by the sweep, which did not know its parent; its subtree is checked.
          parent_[child] = parent;
          break;
        case Mark::kUnseen:
          parent_[child] = parent;
          mark_[child] = Mark::kOpen;
          path.push_back({child, 0});
          break;
      }
    }
    return absl::OkStatus();
  }

  // `node` is on the path: the path from it, parent to child, is the cycle.
  absl::Status Cycle(const std::vector<Frame>& path, int node) const {
    size_t first = path.size() - 1;
    while (path[first].node != node) --first;
    const size_t length = path.size() - first;
    std::string chain;
    for (size_t i = first; i < path.size() && i < first + kCycleShown; ++i)
      absl::StrAppend(&chain, "nodes[", path[i].node, "] -> ");
    if (length > kCycleShown) absl::StrAppend(&chain, "... -> ");
    absl::StrAppend(&chain, "nodes[", node, "]");
    return Refuse(absl::StrCat(NodeName(model_, node), ": is its own ancestor (", chain,
                               ", parent to child: a cycle of ", length,
                               length == 1 ? " node" : " nodes", ")", kTree));
  }

  absl::Status RootAndChild(int node, int scene, int parent = -1) const {
    return Refuse(absl::StrCat(NodeName(model_, node), ": a root of scenes[", scene,
                               "] and a child of ",
                               NodeName(model_, parent >= 0 ? parent : parent_[node]), kTree));
  }

  std::string Existing() const {
    return count_ == 0 ? "the file has no nodes" : absl::StrCat("nodes 0..", count_ - 1);
  }

  const tinygltf::Model& model_;
  const int count_;
  std::vector<Mark> mark_;
  std::vector<int> parent_;
  std::vector<int> root_of_;  // the first scene that lists the node as a root
};

}  // namespace

std::string NodeName(const tinygltf::Model& model, int node) {
  std::string out = absl::StrCat("nodes[", node, "]");
  if (node < 0 || node >= static_cast<int>(model.nodes.size())) return out;
  const std::string& name = model.nodes[node].name;
  if (name.empty()) return out;
  if (name.size() <= kNameShown) return absl::StrCat(out, " ('", name, "')");
  size_t cut = kNameShown;  // not inside a UTF-8 sequence
  while (cut > 0 && (static_cast<unsigned char>(name[cut]) & 0xC0) == 0x80) --cut;
  return absl::StrCat(out, " ('", name.substr(0, cut), "...')");
}

absl::StatusOr<NodeTree> NodeTree::Check(const tinygltf::Model& model) {
  auto parent = TreeCheck(model).Run();
  if (!parent.ok()) return parent.status();
  return NodeTree(model, *std::move(parent));
}

std::vector<int> NodeTree::Roots() const {
  std::vector<int> roots;
  for (size_t n = 0; n < parent_.size(); ++n)
    if (parent_[n] < 0) roots.push_back(static_cast<int>(n));
  return roots;
}

std::vector<int> NodeTree::DepthFirst(std::span<const int> roots) const {
  std::vector<int> order, pending(roots.rbegin(), roots.rend());
  while (!pending.empty()) {
    const int node = pending.back();
    pending.pop_back();
    order.push_back(node);
    const std::vector<int>& children = model_->nodes[node].children;
    pending.insert(pending.end(), children.rbegin(), children.rend());
  }
  return order;
}

}  // namespace aperture
