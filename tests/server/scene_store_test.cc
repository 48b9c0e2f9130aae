// The scene store: found by id, bounded by count and by
// bytes, least recently used scenes dropped first, scenes in use never.
#include "scene_store.h"

#include <gtest/gtest.h>

namespace aperture {
namespace {

std::shared_ptr<const Scene> MakeScene(const std::string& name) {
  auto scene = std::make_shared<Scene>();
  scene->name = name;
  return scene;
}

// Reserves `bytes` and puts a scene named `id` under them.
void Load(SceneStore& store, const std::string& id, uint64_t bytes) {
  auto room = store.Reserve(bytes, "test");
  ASSERT_TRUE(room.ok()) << room.status();
  store.Put(id, MakeScene(id), std::nullopt, *std::move(room));
}

TEST(SceneStore, TheLeastRecentlyUsedGoesFirstWhenTheCountIsFull) {
  SceneStore store(2, 1000);
  Load(store, "a", 1);
  Load(store, "b", 1);
  ASSERT_NE(store.Find("a"), nullptr);  // "a" used after "b"
  Load(store, "c", 1);
  EXPECT_EQ(store.size(), 2u);
  EXPECT_EQ(store.Find("b"), nullptr);
  EXPECT_NE(store.Find("a"), nullptr);
  EXPECT_EQ(store.bytes(), 2u);  // "b"'s bytes went with it
  EXPECT_EQ(store.evicted(), 1u);
}

TEST(SceneStore, BytesMakeRoomFromScenesNobodyHolds) {
  SceneStore store(64, 100);
  Load(store, "a", 40);
  Load(store, "b", 40);
  std::shared_ptr<const Scene> held = store.Find("a");  // a frame renders "a"
  Load(store, "c", 40);                                 // "b" goes, not "a"
  EXPECT_EQ(store.Find("b"), nullptr);
  EXPECT_NE(store.Find("a"), nullptr);
  EXPECT_EQ(store.bytes(), 80u);

  // Every scene held: no room, and nothing dropped.
  std::shared_ptr<const Scene> also_held = store.Find("c");
  auto full = store.Reserve(40, "40 bytes");
  ASSERT_FALSE(full.ok());
  EXPECT_TRUE(absl::IsResourceExhausted(full.status()));
  EXPECT_NE(full.status().message().find("--max-scenes-mb"), std::string::npos);
  EXPECT_EQ(store.size(), 2u);

  // A scene larger than the whole budget is refused whatever is loaded.
  auto alone = store.Reserve(101, "101 bytes");
  ASSERT_FALSE(alone.ok());
  EXPECT_NE(alone.status().message().find("this request alone needs"), std::string::npos);
}

// A scene somebody holds (a stream renders it) is not dropped for the count either: the least
// recently used one nobody holds goes instead, and while all are held the count is exceeded.
TEST(SceneStore, TheCountDropsOnlyScenesNobodyHolds) {
  SceneStore store(2, 1000);
  Load(store, "a", 1);
  std::shared_ptr<const Scene> held = store.Find("a");
  Load(store, "b", 1);
  Load(store, "c", 1);  // "a" is the least recently used, but held: "b" goes
  EXPECT_NE(store.Find("a"), nullptr);
  EXPECT_EQ(store.Find("b"), nullptr);
  EXPECT_EQ(store.evicted(), 1u);
  std::shared_ptr<const Scene> also_held = store.Find("c");
  Load(store, "d", 1);  // every other scene held: "d" is kept past the count
  EXPECT_EQ(store.size(), 3u);
  EXPECT_NE(store.Find("d"), nullptr);
  held.reset();
  also_held.reset();
  Load(store, "e", 1);  // let go: back to the count, the least recently used first
  EXPECT_EQ(store.size(), 2u);
  EXPECT_NE(store.Find("e"), nullptr);
  EXPECT_NE(store.Find("d"), nullptr);
}

}  // namespace
}  // namespace aperture
