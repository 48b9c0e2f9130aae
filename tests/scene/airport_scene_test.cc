// The built-in airport: a real map's runway where the camera expects it, cut-out
// trees and a glass cab, and the aircraft a live channel moves.
#include "scene/airport_scene.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "render/frame_renderer.h"
#include "scene/airport_runways.h"
#include "scene/builtin_scenes.h"
#include "scene/demo_scene.h"
#include "scene/runway_markings.h"
#include "scene/scene_builder.h"
#include "support/map_texel.h"

namespace aperture {
namespace {

using testing::MapAt;

bool IsRunway(const Rgba& c) {  // runway asphalt #383838 or its white markings #F0F0F0
  auto near = [&](float v) { return std::abs(c.r - v) < 0.01f && c.g == c.r && c.b == c.r; };
  return near(0x38 / 255.0f) || near(0xF0 / 255.0f);
}

TEST(AirportScene, TheMapsRunwayRunsAlongTheApproach) {
  auto scene = BuildScene(MakeAirportScene());
  ASSERT_TRUE(scene.ok()) << scene.status();
  // Runway 18R/36L: 3,800 m by 60 m from its south end at z = 200 along -z. Its centreline,
  // every 10 m, is runway; 45 m to either side is not.
  int centre = 0, beside = 0, samples = 0;
  for (double z = 190; z > 200 - 3790; z -= 10, ++samples) {
    centre += IsRunway(MapAt(*scene, 0, z));
    beside += IsRunway(MapAt(*scene, -45, z)) + IsRunway(MapAt(*scene, 45, z));
  }
  EXPECT_GE(centre, samples * 99 / 100) << "of " << samples;
  EXPECT_LE(beside, samples / 50) << "of " << 2 * samples;
  // Past its ends it is not.
  EXPECT_FALSE(IsRunway(MapAt(*scene, 0, 230)));
  EXPECT_FALSE(IsRunway(MapAt(*scene, 0, 200 - 3830)));
}

TEST(AirportScene, HasCutOutTreesAGlassCabAndTheMovingAircraft) {
  const v1::Scene proto = MakeAirportScene();
  int mask = 0, blend = 0;
  for (const v1::Material& m : proto.materials()) {
    mask += m.alpha_mode() == v1::ALPHA_MODE_MASK;
    blend += m.alpha_mode() == v1::ALPHA_MODE_BLEND;
  }
  EXPECT_EQ(mask, 1);
  EXPECT_EQ(blend, 1);
  bool aircraft = false;
  for (const v1::Object& o : proto.objects()) aircraft = aircraft || o.name() == kDemoAircraft;
  EXPECT_TRUE(aircraft);
  auto builtin = FindBuiltinScene("airport");
  ASSERT_TRUE(builtin.ok()) << builtin.status();
  EXPECT_EQ(builtin->scene.name(), "airport-schiphol");
}

TEST(AirportScene, RendersTheTreesCutOutAgainstTheSky) {
  auto scene = BuildScene(MakeAirportScene());
  ASSERT_TRUE(scene.ok()) << scene.status();
  // Looking west along the tree rows from between them and the runway, level: above the
  // horizon, a tree's pixels are either its leaves (green over red and blue) or the sky.
  Camera camera;
  camera.position = {-100, 6, 120};
  camera.yaw_deg = 90;
  camera.vertical_fov_deg = 40;
  RenderSettings settings;
  settings.width = 160;
  settings.height = 90;
  settings.threads = 2;
  auto frame = RenderFrame(*scene, camera, settings);
  ASSERT_TRUE(frame.ok()) << frame.status();
  int leaves = 0, sky = 0;
  for (int y = 0; y < 40; ++y)
    for (int x = 0; x < 160; ++x) {
      const Rgba p = frame->image.at(x, y);
      if (p.b > p.g && p.b > 0.5f) ++sky;
      if (p.g > p.r && p.g > p.b) ++leaves;
    }
  EXPECT_GT(leaves, 50);
  EXPECT_GT(sky, 50);
}

TEST(AirportScene, TheDefaultViewIsTwoMilesOutAndShowsTheMarkings) {
  auto builtin = FindBuiltinScene("airport");
  ASSERT_TRUE(builtin.ok()) << builtin.status();
  const Camera& camera = builtin->camera;
  // 2 NM (3,704 m) before 36L's threshold at z = 200, on the 3 degree path through 300 m past it.
  EXPECT_NEAR(camera.position.x, 0, 1e-9);
  EXPECT_NEAR(camera.position.z, 200 + 3704, 1e-9);
  EXPECT_NEAR(camera.position.y, (3704 + 300) * std::tan(3 * kPi / 180), 1e-9);
  EXPECT_EQ(camera.yaw_deg, 0);
  // Both runways carry their markings.
  int runways = 0;
  for (const v1::Mesh& mesh : builtin->scene.meshes())
    runways += mesh.id() == "runway-36L" || mesh.id() == "runway-36C";
  EXPECT_EQ(runways, 2);

  auto scene = BuildScene(builtin->scene);
  ASSERT_TRUE(scene.ok()) << scene.status();
  RenderSettings settings;
  settings.width = 960;
  settings.height = 540;
  settings.threads = 2;
  auto frame = RenderFrame(*scene, camera, settings);
  ASSERT_TRUE(frame.ok()) << frame.status();
  // The pixel where a world point on the ground lands.
  const FrustumTangents t = ResolveFrustum(camera, settings.width, settings.height);
  const Mat3 to_camera = camera.Orientation().Transposed();
  auto luminance_at = [&](double x, double z) {
    const Vec3 c = to_camera * (Vec3{x, 0, z} - camera.position);
    const int px = static_cast<int>((c.x / -c.z - t.left) / (t.right - t.left) * settings.width);
    const int py = static_cast<int>((t.top - c.y / -c.z) / (t.top - t.bottom) * settings.height);
    EXPECT_TRUE(px >= 0 && px < settings.width && py >= 0 && py < settings.height);
    const Rgba p = frame->image.at(std::clamp(px, 0, settings.width - 1),
                                   std::clamp(py, 0, settings.height - 1));
    return 0.2126f * p.r + 0.7152f * p.g + 0.0722f * p.b;
  };
  // The aiming point's stripes (400 to 445 m in, 9 to 18 m off the centre line) show brighter
  // than the bare asphalt beside them and than the runway between the markings further on.
  for (double side : {-1.0, 1.0}) {
    const float paint = luminance_at(side * 13.5, 200 - 422.5);
    EXPECT_GT(paint, luminance_at(side * 24, 200 - 422.5) + 0.05f) << side;
    EXPECT_GT(paint, luminance_at(side * 13.5, 200 - 1300) + 0.05f) << side;
  }
}

}  // namespace
}  // namespace aperture
