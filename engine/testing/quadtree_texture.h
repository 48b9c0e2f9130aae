// The comparison format of seed 001, section 2.6 (its ref. 10): an incomplete quaternary tree.
// The texture's enclosing 2^k square is split recursively; a square of one colour is a leaf and is
// not split further (hence "incomplete"); squares wholly outside a non-square texture are leaves
// that merge with any colour.
//
// Ref. 10 is not available to us, so the encoding is ours, chosen as a fair pointer-free tree that
// supports random access in place: an internal node is 4 consecutive 32-bit words, one per child in
// quadrant order (x bit + 2 y bit); a word with the top bit set is a leaf holding a palette index,
// otherwise it is the word offset of the child node. Stored size = 16-byte header + palette +
// 4 bytes per word, in memory and on disk alike.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "texture/packed/palette.h"

namespace aperture::packed {

class QuadtreeTexture {
 public:
  static QuadtreeTexture Build(const IndexedImage& image);

  // Descends from the root: one dependent load per level until a leaf.
  uint8_t PaletteIndexAt(uint32_t x, uint32_t y) const {
    uint32_t word = root_;
    int level = order_;
    while (!(word & kLeaf)) {
      --level;
      word = nodes_[word + (((x >> level) & 1u) | (((y >> level) & 1u) << 1))];
    }
    return static_cast<uint8_t>(word);
  }
  uint32_t ColorAt(uint32_t x, uint32_t y) const { return palette_[PaletteIndexAt(x, y)]; }
  // colours[i] = ColorAt(xs[i], ys[i]), descending 16 texels in lockstep (a level of all of them
  // at a time, without a branch per texel), the same treatment as RunIndex::ColorsAt.
  void ColorsAt(std::span<const uint32_t> xs, std::span<const uint32_t> ys,
                std::span<uint32_t> colours) const;

  size_t node_count() const { return nodes_.size() / 4; }
  size_t leaf_count() const { return leaves_; }
  size_t byte_size() const { return 16 + 4 * palette_.size() + 4 * nodes_.size(); }

 private:
  static constexpr uint32_t kLeaf = 0x80000000u;
  struct Subtree {
    uint32_t word;
    bool uniform;  // a leaf (or wholly outside: `outside`)
    bool outside;
  };
  Subtree BuildSquare(const IndexedImage& image, int level, uint32_t x0, uint32_t y0);

  int order_ = 0;
  uint32_t root_ = kLeaf;
  size_t leaves_ = 0;
  std::vector<uint32_t> palette_;
  std::vector<uint32_t> nodes_;
};

}  // namespace aperture::packed
