// Summed-area tables in the shared store: the block round-trips exactly, a damaged block
// is refused, and a scene traced with its tables mapped from the store renders the same pixels as
// one with tables in memory, the second build attaching instead of building.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <random>

#include "render/trace_renderer.h"
#include "scene/scene_builder.h"
#include "testing/curved_scenes.h"
#include "texture/summed_area_levels.h"
#include "texture/summed_area_table.h"
#include "texture/texture_entries.h"

namespace aperture {
namespace {

namespace fs = std::filesystem;

TEST(SummedAreaTableStore, BlockRoundTripsAndDamageIsRefused) {
  Image img(8, 4);
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u01(0, 1);
  for (Rgba& t : img.texels()) t = {u01(rng), u01(rng), u01(rng), 1};
  const SummedAreaTable built(img, 3);
  const std::vector<std::byte> block = built.ToBytes();
  auto view = SummedAreaTable::View(block);
  ASSERT_TRUE(view.ok()) << view.status();
  EXPECT_EQ((*view)->width(), 8);
  EXPECT_EQ((*view)->channels(), 3);
  for (double x0 : {0.0, 0.3, 2.7})
    for (double y1 : {0.9, 2.2, 4.0}) {
      const auto a = built.Integrate(x0, 0.1, x0 + 3.4, y1),
                 b = (*view)->Integrate(x0, 0.1, x0 + 3.4, y1);
      for (int c = 0; c < 4; ++c) EXPECT_EQ(a[c], b[c]);
    }
  EXPECT_FALSE(SummedAreaTable::View(std::span(block).first(block.size() - 8)).ok());
  std::vector<std::byte> bad = block;
  bad[0] = std::byte{'X'};
  EXPECT_FALSE(SummedAreaTable::View(bad).ok());
  EXPECT_FALSE(SummedAreaTable::View(std::span(block).first(16)).ok());
}

TEST(SummedAreaTableStore, LevelsBlockRoundTripsAndDamageIsRefused) {
  // A 16 x 4 texture: levels 16x4, 8x2 (the next, 4x1, is under 2 texels on a side).
  Image img(16, 4);
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u01(0, 1);
  for (Rgba& t : img.texels()) t = {u01(rng), u01(rng), u01(rng), 1};
  const MipPyramid pyramid(img);
  EXPECT_EQ(SummedAreaLevelCount(pyramid), 2);
  const std::vector<std::byte> block = SummedAreaLevelsToBytes(pyramid, 3);
  auto levels = ViewSummedAreaLevels(block);
  ASSERT_TRUE(levels.ok()) << levels.status();
  ASSERT_EQ(levels->size(), 2u);
  const auto built = BuildSummedAreaLevels(pyramid, 3);
  for (int l = 0; l < 2; ++l) {
    EXPECT_EQ((*levels)[l]->width(), pyramid.level(l).width());
    const auto a = built[l]->Integrate(0.3, 0.2, 1.9, 1.7),
               b = (*levels)[l]->Integrate(0.3, 0.2, 1.9, 1.7);
    for (int c = 0; c < 3; ++c) EXPECT_EQ(a[c], b[c]);
  }
  // Truncated, a wrong magic, a level index pointing past the end.
  EXPECT_FALSE(ViewSummedAreaLevels(std::span(block).first(block.size() - 8)).ok());
  EXPECT_FALSE(ViewSummedAreaLevels(std::span(block).first(20)).ok());
  std::vector<std::byte> bad = block;
  bad[0] = std::byte{'X'};
  EXPECT_FALSE(ViewSummedAreaLevels(bad).ok());
  bad = block;
  const uint64_t past = block.size() + 8;
  std::memcpy(bad.data() + 32, &past, sizeof(past));
  auto refused = ViewSummedAreaLevels(bad);
  ASSERT_FALSE(refused.ok());
  EXPECT_NE(refused.status().message().find("level 0"), std::string::npos) << refused.status();
}

TEST(SummedAreaTableStore, TheBlocksSizeIsKnownBeforeItIsBuilt) {
  for (auto [w, h] : {std::pair{1, 1}, {16, 4}, {5, 7}, {64, 64}, {33, 2}})
    for (int channels : {1, 3, 4}) {
      SCOPED_TRACE(std::to_string(w) + "x" + std::to_string(h) + "x" + std::to_string(channels));
      Image img(w, h);
      const MipPyramid pyramid(img);
      EXPECT_EQ(SummedAreaTable::BlockBytes(w, h, channels),
                SummedAreaTable(img, channels).ToBytes().size());
      EXPECT_EQ(SummedAreaLevelsBytes(pyramid, channels),
                SummedAreaLevelsToBytes(pyramid, channels).size());
    }
  // A 4096 x 4096 RGB texture's tables, the size a store budget is weighed against: 4.3 GB.
  EXPECT_EQ(SummedAreaTable::BlockBytes(4096, 4096, 3), 32 + size_t{8} * 4098 * 4098 * 3 * 8);
}

TEST(SummedAreaTableStore, TracedSceneFromTheStoreRendersTheSamePixels) {
  const fs::path dir = fs::path("/dev/shm") / ("aperture-sat-test-" + std::to_string(getpid()));
  fs::remove_all(dir);
  auto store = SharedStore::Open(dir.string());
  ASSERT_TRUE(store.ok()) << store.status();
  const CurvedTestScene test = MakeCurvedTestScene(CurvedSceneKind::kCylinder, 128);
  auto scene = BuildScene(test.scene);
  ASSERT_TRUE(scene.ok());
  RenderSettings settings;
  settings.width = 40;
  settings.height = 32;
  settings.threads = 2;
  auto in_memory = TracedScene::Build(*scene);
  auto stored = TracedScene::Build(*scene, *store);
  auto again = TracedScene::Build(*scene, *store);
  ASSERT_TRUE(in_memory.ok() && stored.ok() && again.ok());
  EXPECT_EQ((*store)->counters().built, 1u);
  auto a = (*in_memory)->Render(test.camera, settings, {});
  auto b = (*again)->Render(test.camera, settings, {});
  ASSERT_TRUE(a.ok() && b.ok());
  for (size_t i = 0; i < a->image.texels().size(); ++i) {
    const Rgba &p = a->image.texels()[i], &q = b->image.texels()[i];
    ASSERT_TRUE(p.r == q.r && p.g == q.g && p.b == q.b) << i;
  }
  fs::remove_all(dir);
}

// Tables larger than the store's budget are refused before they are built, naming the texture,
// the tables' size and the budget; nothing is written to the store.
TEST(SummedAreaTableStore, TablesOverTheStoresBudgetAreRefusedUnbuilt) {
  const fs::path dir = fs::path("/dev/shm") / ("aperture-sat-budget-" + std::to_string(getpid()));
  fs::remove_all(dir);
  auto store = SharedStore::Open(dir.string());
  ASSERT_TRUE(store.ok()) << store.status();
  (*store)->SetBudget(1 << 20);
  // The cylinder's 128 x 128 texture: its tables take about 4.5 MiB.
  const CurvedTestScene test = MakeCurvedTestScene(CurvedSceneKind::kCylinder, 128);
  auto scene = BuildScene(test.scene);
  ASSERT_TRUE(scene.ok());
  auto refused = TracedScene::Build(*scene, *store);
  ASSERT_FALSE(refused.ok());
  EXPECT_TRUE(absl::IsResourceExhausted(refused.status())) << refused.status();
  const std::string message(refused.status().message());
  EXPECT_NE(message.find("128 x 128 texels"), std::string::npos) << message;
  EXPECT_NE(message.find("an entry of 4 MiB"), std::string::npos) << message;
  EXPECT_NE(message.find("budget of 1 MiB"), std::string::npos) << message;
  EXPECT_EQ((*store)->counters().built, 0u);
  EXPECT_EQ((*store)->TotalBytes(), 0u);
  fs::remove_all(dir);
}

// Without a store the tables are built in memory, and refused before they are built when they
// would pass the budget of what the server holds in memory (--max-store-mb); within it they are.
TEST(SummedAreaTableStore, TablesInMemoryOverTheBudgetAreRefusedUnbuilt) {
  const CurvedTestScene test = MakeCurvedTestScene(CurvedSceneKind::kCylinder, 128);
  auto scene = BuildScene(test.scene);
  ASSERT_TRUE(scene.ok());
  auto refused = TracedScene::Build(*scene, nullptr, {}, 1 << 20);
  ASSERT_FALSE(refused.ok());
  EXPECT_TRUE(absl::IsResourceExhausted(refused.status())) << refused.status();
  const std::string message(refused.status().message());
  EXPECT_NE(message.find("4 MiB, built in memory"), std::string::npos) << message;
  EXPECT_NE(message.find("budget of 1 MiB"), std::string::npos) << message;
  EXPECT_TRUE(TracedScene::Build(*scene, nullptr, {}, 8 << 20).ok());
}

// A raytraced frame's deadline stops the build of its summed-area tables.
TEST(SummedAreaTableStore, AStoppedBuildIsCancelled) {
  const CurvedTestScene test = MakeCurvedTestScene(CurvedSceneKind::kCylinder, 128);
  auto scene = BuildScene(test.scene);
  ASSERT_TRUE(scene.ok());
  auto stopped = TracedScene::Build(*scene, nullptr, [] { return true; });
  ASSERT_FALSE(stopped.ok());
  EXPECT_TRUE(absl::IsCancelled(stopped.status())) << stopped.status();
  EXPECT_TRUE(TracedScene::Build(*scene, nullptr, [] { return false; }).ok());
}

}  // namespace
}  // namespace aperture
