#include "testing/quadtree_texture.h"

#include <algorithm>

#include "texture/packed/space_filling_curve.h"

namespace aperture::packed {

QuadtreeTexture::Subtree QuadtreeTexture::BuildSquare(const IndexedImage& image, int level,
                                                      uint32_t x0, uint32_t y0) {
  if (x0 >= image.width || y0 >= image.height) return {kLeaf, true, true};
  if (level == 0) return {kLeaf | image.at(x0, y0), true, false};
  const int half = level - 1;
  Subtree child[4];
  for (uint32_t q = 0; q < 4; ++q)
    child[q] = BuildSquare(image, half, x0 + ((q & 1u) << half), y0 + ((q >> 1) << half));
  // One colour over every child that holds texels: this square is a leaf.
  bool uniform = true;
  int colour = -1;
  for (const Subtree& c : child) {
    if (!c.uniform) {
      uniform = false;
      break;
    }
    if (c.outside) continue;
    if (colour >= 0 && static_cast<uint32_t>(colour) != (c.word & 0xFFu)) uniform = false;
    colour = static_cast<int>(c.word & 0xFFu);
  }
  if (uniform) return {kLeaf | static_cast<uint32_t>(colour), true, false};
  const uint32_t at = static_cast<uint32_t>(nodes_.size());
  for (const Subtree& c : child) {
    nodes_.push_back(c.word);
    if (c.word & kLeaf) ++leaves_;
  }
  return {at, false, false};
}

QuadtreeTexture QuadtreeTexture::Build(const IndexedImage& image) {
  QuadtreeTexture tree;
  tree.order_ = CurveOrder(image.width, image.height);
  tree.palette_ = image.palette;
  const Subtree root = tree.BuildSquare(image, tree.order_, 0, 0);
  tree.root_ = root.word;
  if (root.word & kLeaf) tree.leaves_ = 1;
  return tree;
}

void QuadtreeTexture::ColorsAt(std::span<const uint32_t> xs, std::span<const uint32_t> ys,
                               std::span<uint32_t> colours) const {
  if (root_ & kLeaf) {  // one colour, no nodes
    std::fill(colours.begin(), colours.end(), palette_[root_ & 0xFFu]);
    return;
  }
  constexpr size_t kLanes = 16;
  for (size_t begin = 0; begin < xs.size(); begin += kLanes) {
    const size_t lanes = std::min(kLanes, xs.size() - begin);
    uint32_t word[kLanes];
    for (size_t l = 0; l < kLanes; ++l) word[l] = root_;
    for (int level = order_ - 1; level >= 0; --level) {
      uint32_t inner = 0;
      for (size_t l = 0; l < lanes; ++l) {
        const uint32_t x = xs[begin + l], y = ys[begin + l];
        const bool leaf = word[l] & kLeaf;
        // A leaf reads word 0 (always there) and keeps its word.
        const uint32_t child =
            nodes_[leaf ? 0 : word[l] + (((x >> level) & 1u) | (((y >> level) & 1u) << 1))];
        word[l] = leaf ? word[l] : child;
        inner |= ~word[l] & kLeaf;
      }
      if (!inner) break;
    }
    for (size_t l = 0; l < lanes; ++l) colours[begin + l] = palette_[word[l] & 0xFFu];
  }
}

}  // namespace aperture::packed
