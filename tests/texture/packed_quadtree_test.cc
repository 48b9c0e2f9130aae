#include <gtest/gtest.h>

#include "testing/quadtree_texture.h"
#include "texture/packed_test_images.h"

namespace aperture::packed {
namespace {

using testing::RandomIndexedImage;

TEST(PackedQuadtree, EveryTexelReadsBack) {
  for (auto [w, h] : {std::pair{1u, 1u}, {1u, 37u}, {37u, 91u}, {64u, 64u}, {100u, 3u}}) {
    for (bool blocky : {false, true}) {
      const IndexedImage image = RandomIndexedImage(w, h, 7, w + h, blocky);
      const QuadtreeTexture tree = QuadtreeTexture::Build(image);
      for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x) ASSERT_EQ(tree.PaletteIndexAt(x, y), image.at(x, y));
    }
  }
}

TEST(PackedQuadtree, UniformSquaresAreLeaves) {
  const QuadtreeTexture one = QuadtreeTexture::Build(RandomIndexedImage(300, 200, 1, 1));
  EXPECT_EQ(one.node_count(), 0u);
  EXPECT_EQ(one.leaf_count(), 1u);
  // Left half colour 0, right half colour 1: the root splits once.
  IndexedImage halves = RandomIndexedImage(64, 64, 2, 1);
  for (uint32_t y = 0; y < 64; ++y)
    for (uint32_t x = 0; x < 64; ++x) halves.indices[y * 64 + x] = x < 32 ? 0 : 1;
  const QuadtreeTexture tree = QuadtreeTexture::Build(halves);
  EXPECT_EQ(tree.node_count(), 1u);
  EXPECT_EQ(tree.leaf_count(), 4u);
}

}  // namespace
}  // namespace aperture::packed
