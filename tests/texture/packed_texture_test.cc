#include "texture/packed/packed_texture.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

#include "texture/packed/curve_walk.h"
#include "texture/packed/palette.h"
#include "texture/packed/rgba8_image.h"
#include "texture/packed/run_index.h"
#include "texture/packed_test_images.h"

namespace aperture::packed {
namespace {

using testing::RandomIndexedImage;

// Runs straight from the definition (seed 001, section 2.1): texels sorted by curve step, a run
// per maximal sequence of equal indices, S_i = step of its last texel.
void ExpectRunsMatchDefinition(const IndexedImage& image, const PackedTextureView& v) {
  std::vector<std::pair<uint32_t, uint8_t>> texels;
  for (uint32_t y = 0; y < image.height; ++y)
    for (uint32_t x = 0; x < image.width; ++x)
      texels.push_back({CurveStep(v.curve(), v.order(), x, y), image.at(x, y)});
  std::sort(texels.begin(), texels.end());
  std::vector<uint32_t> steps;
  std::vector<uint8_t> indices;
  for (size_t i = 0; i < texels.size(); ++i) {
    if (i + 1 == texels.size() || texels[i + 1].second != texels[i].second) {
      steps.push_back(texels[i].first);
      indices.push_back(texels[i].second);
    }
  }
  ASSERT_EQ(std::vector<uint32_t>(v.steps().begin(), v.steps().end()), steps);
  ASSERT_EQ(std::vector<uint8_t>(v.indices().begin(), v.indices().end()), indices);
}

void ExpectLosslessRoundTrip(const IndexedImage& image, Curve curve) {
  SCOPED_TRACE(std::string(CurveName(curve)) + " " + std::to_string(image.width) + "x" +
               std::to_string(image.height) + ", " + std::to_string(image.palette.size()) +
               " colours");
  auto packed = PackTexture(image, curve);
  ASSERT_TRUE(packed.ok()) << packed.status();
  const PackedTextureView& v = packed->view();
  const IndexedImage back = UnpackTexture(v);
  ASSERT_EQ(back.palette, image.palette);
  ASSERT_EQ(back.indices, image.indices);
  // Access without unpacking: plain binary search, indexed search, batched.
  const RunIndex index(v);
  std::vector<uint32_t> xs, ys, batch(size_t{image.width} * image.height);
  for (uint32_t y = 0; y < image.height; ++y) {
    for (uint32_t x = 0; x < image.width; ++x) {
      ASSERT_EQ(v.PaletteIndexAt(x, y), image.at(x, y)) << x << "," << y;
      ASSERT_EQ(index.PaletteIndexAt(x, y), image.at(x, y)) << x << "," << y;
      xs.push_back(x);
      ys.push_back(y);
    }
  }
  index.ColorsAt(xs, ys, batch);
  for (size_t i = 0; i < batch.size(); ++i) ASSERT_EQ(batch[i], image.palette[image.indices[i]]);
  // Other cell sizes (below 4 x 4 and above 64 x 64 texels without detail records, between with
  // them), and without the single-run shortcut (the path of huge textures).
  using Details = RunIndex::Options::Details;
  for (int bits : {0, 1, 2, 3, 5, 6, 30}) {
    for (auto [shortcut, details] : {std::pair{true, Details::kAuto},
                                     {true, Details::kAlways},
                                     {true, Details::kNever},
                                     {false, Details::kAuto}}) {
      const RunIndex other(
          v, {.cell_bits = bits, .single_run_shortcut = shortcut, .details = details});
      for (size_t i = 0; i < xs.size(); ++i) {
        ASSERT_EQ(other.PaletteIndexAt(xs[i], ys[i]), image.indices[i]) << bits << shortcut;
        ASSERT_EQ(other.RunAt(xs[i], ys[i]), v.RunOfStep(v.StepOf(xs[i], ys[i])));
      }
      std::fill(batch.begin(), batch.end(), 0);
      other.ColorsAt(xs, ys, batch);
      for (size_t i = 0; i < batch.size(); ++i)
        ASSERT_EQ(batch[i], image.palette[image.indices[i]]) << bits << shortcut;
    }
  }
}

TEST(PackedTexture, LosslessRoundTripOnGeneratedImages) {
  const std::vector<std::pair<uint32_t, uint32_t>> sizes = {
      {1, 1}, {1, 37}, {53, 1}, {2, 2}, {37, 91}, {64, 64}, {100, 3}, {129, 65}};
  uint64_t seed = 1;
  for (Curve curve : {Curve::kHilbert, Curve::kMorton}) {
    for (auto [w, h] : sizes) {
      for (uint32_t colours : {1u, 2u, 7u, 256u}) {
        ExpectLosslessRoundTrip(RandomIndexedImage(w, h, colours, ++seed), curve);
        ExpectLosslessRoundTrip(RandomIndexedImage(w, h, colours, ++seed, /*blocky=*/true), curve);
      }
    }
  }
}

TEST(PackedTexture, RunsAreExactlyThePapersTuples) {
  for (Curve curve : {Curve::kHilbert, Curve::kMorton}) {
    for (auto [w, h] : {std::pair{8u, 8u}, {37u, 91u}, {1u, 200u}, {100u, 3u}}) {
      const IndexedImage image = RandomIndexedImage(w, h, 6, w * 131 + h, true);
      auto packed = PackTexture(image, curve);
      ASSERT_TRUE(packed.ok());
      ExpectRunsMatchDefinition(image, packed->view());
    }
  }
}

TEST(PackedTexture, OneColourIsOneRunEndingAtTheLastTexel) {
  IndexedImage image = RandomIndexedImage(300, 7, 1, 3);
  for (Curve curve : {Curve::kHilbert, Curve::kMorton}) {
    auto packed = PackTexture(image, curve);
    ASSERT_TRUE(packed.ok());
    ASSERT_EQ(packed->view().run_count(), 1u);
    EXPECT_EQ(packed->view().steps()[0], LastStepInside(curve, 300, 7));
  }
}

TEST(PackedTexture, ThinAndTallTexturesUpToTheLimit) {
  // 1 x 65536: a 2^32-step curve, of which 65536 steps are visited.
  for (Curve curve : {Curve::kHilbert, Curve::kMorton}) {
    ExpectLosslessRoundTrip(RandomIndexedImage(1, 65536, 5, 17, true), curve);
    ExpectLosslessRoundTrip(RandomIndexedImage(65536, 1, 256, 18), curve);
  }
}

TEST(PackedTexture, RefusesSizesAboveTheLimit) {
  IndexedImage image;
  image.width = 65537;
  image.height = 1;
  image.palette = {0};
  image.indices.assign(65537, 0);
  auto packed = PackTexture(image, Curve::kHilbert);
  ASSERT_FALSE(packed.ok());
  EXPECT_NE(packed.status().message().find("65536"), std::string::npos);
}

TEST(PackedTexture, WorksInPlaceFromAnyAlignedBuffer) {
  const IndexedImage image = RandomIndexedImage(50, 40, 9, 5, true);
  auto packed = PackTexture(image, Curve::kHilbert);
  ASSERT_TRUE(packed.ok());
  // As a message payload would carry it.
  const std::string message(reinterpret_cast<const char*>(packed->bytes().data()),
                            packed->bytes().size());
  auto view = PackedTextureView::FromBytes(
      {reinterpret_cast<const uint8_t*>(message.data()), message.size()});
  ASSERT_TRUE(view.ok()) << view.status();
  for (uint32_t y = 0; y < 40; ++y)
    for (uint32_t x = 0; x < 50; ++x) ASSERT_EQ(view->PaletteIndexAt(x, y), image.at(x, y));
}

TEST(PackedTexture, ViewRejectsDamagedBytes) {
  const IndexedImage image = RandomIndexedImage(50, 40, 9, 5, true);
  auto packed = PackTexture(image, Curve::kMorton);
  ASSERT_TRUE(packed.ok());
  const std::span<const uint8_t> good = packed->bytes();
  PackedHeader h;
  std::memcpy(&h, good.data(), sizeof(h));
  auto damaged = [&](auto change) {
    std::vector<uint64_t> storage((good.size() + 7) / 8);
    uint8_t* bytes = reinterpret_cast<uint8_t*>(storage.data());
    std::memcpy(bytes, good.data(), good.size());
    change(bytes);
    return PackedTextureView::FromBytes({bytes, good.size()});
  };
  EXPECT_TRUE(damaged([](uint8_t*) {}).ok());
  EXPECT_FALSE(damaged([](uint8_t* b) { b[0] ^= 1; }).ok());  // magic
  EXPECT_FALSE(damaged([&](uint8_t* b) {                      // steps not increasing
                 uint32_t* steps = reinterpret_cast<uint32_t*>(b + h.steps_offset);
                 steps[1] = steps[0];
               })
                   .ok());
  EXPECT_FALSE(damaged([&](uint8_t* b) { b[h.indices_offset] = 200; }).ok());  // index range
  EXPECT_FALSE(damaged([&](uint8_t* b) {  // run count over the bytes
                 PackedHeader bad = h;
                 bad.run_count = 0x7FFFFFFF;
                 std::memcpy(b, &bad, sizeof(bad));
               })
                   .ok());
  EXPECT_FALSE(damaged([&](uint8_t* b) {  // offset past the end
                 PackedHeader bad = h;
                 bad.steps_offset = ~uint64_t{0} - 3;
                 std::memcpy(b, &bad, sizeof(bad));
               })
                   .ok());
  EXPECT_FALSE(PackedTextureView::FromBytes(good.first(good.size() - 1)).ok());  // truncated
}

TEST(PackedPalette, ExactPaletteAndQuantization) {
  Rgba8Image rgba;
  rgba.width = 300;
  rgba.height = 2;
  for (uint32_t i = 0; i < 600; ++i)
    rgba.texels.push_back(
        PackRgba8(static_cast<uint8_t>(i % 300), static_cast<uint8_t>(i / 300), 7, 255));
  auto refused = BuildPalette(rgba);
  ASSERT_FALSE(refused.ok());
  EXPECT_NE(refused.status().message().find("--quantize"), std::string::npos);
  auto quantized = BuildPalette(rgba, /*quantize=*/true);
  ASSERT_TRUE(quantized.ok()) << quantized.status();
  EXPECT_LE(quantized->palette.size(), 256u);
  EXPECT_GE(quantized->palette.size(), 200u);
  for (size_t i = 0; i < rgba.texels.size(); ++i) {
    const uint32_t q = quantized->palette[quantized->indices[i]];
    EXPECT_LE(std::abs(int(Channel(q, 0)) - int(Channel(rgba.texels[i], 0))), 2);
  }
  // Exactly 256 colours pass without quantization, and expand back exactly.
  rgba.width = 256;
  rgba.height = 1;
  rgba.texels.resize(256);
  auto exact = BuildPalette(rgba);
  ASSERT_TRUE(exact.ok());
  EXPECT_EQ(exact->palette.size(), 256u);
  EXPECT_EQ(ExpandPalette(*exact).texels, rgba.texels);
}

TEST(PackedTexture, IndexOfANoisyTextureStaysSmall) {
  // 4 x 4 blocks of random colours: every 8 x 8-texel cell holds several runs, so detail records
  // for all of them would cost more than the runs themselves; the default leaves them out.
  IndexedImage image = RandomIndexedImage(512, 512, 256, 5);
  for (uint32_t y = 0; y < 512; ++y)
    for (uint32_t x = 0; x < 512; ++x)
      image.indices[y * 512 + x] = image.indices[(y & ~3u) * 512 + (x & ~3u)];
  auto packed = PackTexture(image, Curve::kHilbert);
  ASSERT_TRUE(packed.ok());
  const PackedTextureView& v = packed->view();
  const RunIndex index(v);
  const RunIndex forced(v, {.details = RunIndex::Options::Details::kAlways});
  EXPECT_LE(index.byte_size(), 12 * v.run_count());
  EXPECT_GT(forced.byte_size(), 12 * v.run_count());
  for (uint32_t y = 0; y < 512; y += 3) {
    for (uint32_t x = 0; x < 512; x += 5) {
      ASSERT_EQ(index.PaletteIndexAt(x, y), image.at(x, y));
      ASSERT_EQ(forced.PaletteIndexAt(x, y), image.at(x, y));
    }
  }
}

TEST(PackedTexture, MapTexturesRoundTrip) {
  for (const char* name : {"osm_eham_schiphol_2048.png", "osm_helsinki_centre_2048.png"}) {
    auto rgba = LoadRgba8Image(std::string(APERTURE_SHARED_DATA) + "/vector/" + name);
    ASSERT_TRUE(rgba.ok()) << rgba.status();
    auto image = BuildPalette(*rgba);
    ASSERT_TRUE(image.ok()) << image.status();
    for (Curve curve : {Curve::kHilbert, Curve::kMorton}) {
      auto packed = PackTexture(*image, curve);
      ASSERT_TRUE(packed.ok());
      EXPECT_EQ(ExpandPalette(UnpackTexture(packed->view())).texels, rgba->texels) << name;
      const RunIndex index(packed->view());
      // Maps get detail records: the index is more than its grid of 8-byte cells.
      const size_t side = size_t{1} << index.cell_bits();
      const size_t grid =
          8 * ((image->width + side - 1) / side) * ((image->height + side - 1) / side);
      EXPECT_GT(index.byte_size(), grid + 1024) << name;
      for (uint32_t y = 0; y < image->height; y += 7)
        for (uint32_t x = 0; x < image->width; x += 5)
          ASSERT_EQ(index.ColorAt(x, y), rgba->at(x, y));
    }
  }
}

}  // namespace
}  // namespace aperture::packed
