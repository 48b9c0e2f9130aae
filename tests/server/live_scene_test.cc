// A channel's scene holds the stored scene it renders: the scene store's budget drops
// other scenes while the channel is open, and the channel's scene once it has ended.
#include "live_scene.h"

#include <gtest/gtest.h>

namespace aperture {
namespace {

// A well-formed scene id (64 lowercase hex digits, as LoadScene gives), all `digit`.
std::string Id(char digit) { return std::string(64, digit); }

// Reserves `bytes` and puts an empty scene named `id` under them.
void Load(SceneStore& store, const std::string& id, uint64_t bytes) {
  auto room = store.Reserve(bytes, "test");
  ASSERT_TRUE(room.ok()) << room.status();
  auto scene = std::make_shared<Scene>();
  scene->name = id;
  store.Put(id, std::move(scene), std::nullopt, *std::move(room));
}

TEST(LiveScene, HoldsItsStoredSceneUntilItEnds) {
  SceneStore store(64, 100);
  Load(store, Id('a'), 40);
  v1::RenderFrameRequest request;
  request.set_scene_id(Id('a'));
  {
    LiveScene live(store);
    {
      auto checked = live.Check(request, nullptr);
      ASSERT_TRUE(checked.ok()) << checked.status();
      auto scene = live.Advance(request, *checked, nullptr);
      ASSERT_TRUE(scene.ok()) << scene.status();
      EXPECT_EQ((*scene)->name, Id('a'));
      EXPECT_FALSE(live.updated());
    }  // the frame is done; the channel stays open
    Load(store, Id('b'), 40);
    Load(store, Id('c'), 40);  // "a" is the least recently used, but the channel holds it
    EXPECT_NE(store.Find(Id('a')), nullptr);
    EXPECT_EQ(store.Find(Id('b')), nullptr);
    // Its next frame finds the scene it holds.
    auto again = live.Advance(request, nullptr, nullptr);
    EXPECT_TRUE(again.ok()) << again.status();
  }
  // Ended: the scene it held may go now.
  Load(store, Id('d'), 40);
  Load(store, Id('e'), 40);
  EXPECT_EQ(store.size(), 2u);
  EXPECT_EQ(store.Find(Id('a')), nullptr);
}

TEST(LiveScene, AMalformedSceneIdIsInvalidAndAnUnknownOneNotFound) {
  SceneStore store(64, 100);
  LiveScene live(store);
  v1::RenderFrameRequest request;
  request.set_scene_id(std::string(100000, 'f'));
  auto checked = live.Check(request, nullptr);
  EXPECT_TRUE(absl::IsInvalidArgument(checked.status())) << checked.status();
  EXPECT_LT(checked.status().message().size(), 200u);
  request.set_scene_id(Id('f'));
  checked = live.Check(request, nullptr);
  EXPECT_TRUE(absl::IsNotFound(checked.status())) << checked.status();
}

}  // namespace
}  // namespace aperture
