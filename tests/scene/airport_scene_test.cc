// The built-in airport (issue 24 part 4): a real map's runway where the camera expects it, cut-out
// trees and a glass cab, and the aircraft a live channel moves.
#include "scene/airport_scene.h"

#include <gtest/gtest.h>

#include <cmath>

#include "render/frame_renderer.h"
#include "scene/builtin_scenes.h"
#include "scene/demo_scene.h"
#include "scene/scene_builder.h"

namespace aperture {
namespace {

// The map's colour at world point (x, 0, z): its nearest texel, through the ground polygon's own
// texture mapping.
Rgba MapAt(const Scene& scene, double x, double z) {
  for (const ScenePolygon& p : scene.polygons) {
    const Material& m = scene.materials[p.material];
    if (m.id != "map") continue;
    const Vec3 at{x, 0, z};
    TextureFootprint f;
    f.u = Dot(p.mapping.su, at) + p.mapping.u0;
    f.v = Dot(p.mapping.sv, at) + p.mapping.v0;
    f.u -= std::floor(f.u), f.v -= std::floor(f.v);
    return scene.textures[m.texture]->Sampler(FilterMode::kNearest).Sample(f);
  }
  ADD_FAILURE() << "no map polygon";
  return {};
}

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

}  // namespace
}  // namespace aperture
