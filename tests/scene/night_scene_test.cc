// The built-in night scene (scene/night_scene.h) carries the night load 14 CFR Part 60 asks of a
// visual system (Appendix A, Table A1A, 6.o): from its own camera at least 15,000 lights and
// 10,000 textured polygons in view, and 16 moving objects, each carrying its own lights; it stays
// within the scene limits, and a small frame of it shows the runway lit.
#include "scene/night_scene.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "raster/projection.h"
#include "render/frame_renderer.h"
#include "render/light_pass.h"
#include "scene/aircraft_lights.h"
#include "scene/builtin_scenes.h"
#include "scene/demo_scene.h"
#include "scene/light_points.h"
#include "scene/scene_builder.h"
#include "scene/scene_update.h"
#include "scene/spot_lights.h"
#include "support/map_texel.h"

namespace aperture {
namespace {

constexpr int kWidth = 1280, kHeight = 720;

// The scene without its haze: in fog each light also projects a halo, and the lights are counted
// once.
const Scene& ClearNight() {
  static const Scene* const scene = [] {
    v1::Scene proto = MakeNightScene();
    proto.clear_fog();
    auto built = BuildScene(proto);
    EXPECT_TRUE(built.ok()) << built.status();
    return new Scene(built.ok() ? *std::move(built) : Scene{});
  }();
  return *scene;
}

RenderSettings FrameSettings(int width, int height) {
  RenderSettings settings;
  settings.width = width;
  settings.height = height;
  return settings;
}

TEST(NightScene, IsTheBuiltInNightWithItsApproachCamera) {
  auto builtin = FindBuiltinScene("night");
  ASSERT_TRUE(builtin.ok()) << builtin.status();
  EXPECT_EQ(builtin->scene.name(), "airport-night");
  const Camera camera = NightCamera();
  EXPECT_EQ(builtin->camera.position.z, camera.position.z);
  // On the 3 degree path to the PAPI's point 300 m past the threshold (z = 200), level with the
  // runway's heading.
  const double from_papi = camera.position.z - (200 - 300);
  EXPECT_NEAR(camera.position.y / from_papi, std::tan(Radians(3)), 1e-9);
  EXPECT_EQ(camera.yaw_deg, 0);
  // The unknown-name error lists it.
  auto unknown = FindBuiltinScene("nite");
  ASSERT_FALSE(unknown.ok());
  EXPECT_NE(unknown.status().message().find("night"), std::string::npos) << unknown.status();
}

// By day: the same polygons and camera, the airport's sun and sky, no lights.
TEST(NightScene, ByDayHasItsPolygonsAndNoLights) {
  auto night = FindBuiltinScene("night");
  auto day = FindBuiltinScene("night-by-day");
  ASSERT_TRUE(night.ok() && day.ok()) << day.status();
  EXPECT_EQ(day->scene.meshes_size(), night->scene.meshes_size());
  EXPECT_EQ(day->scene.objects_size(), night->scene.objects_size());
  EXPECT_EQ(day->scene.lights_size() + day->scene.light_rows_size(), 0);
  EXPECT_EQ(day->scene.spot_lights_size(), 0);
  EXPECT_GT(day->scene.sun().color().r(), 10 * night->scene.sun().color().r());
  EXPECT_EQ(day->camera.position.z, night->camera.position.z);
}

TEST(NightScene, StaysWithinTheSceneLimits) {
  const v1::Scene proto = MakeNightScene();
  // Rows keep the scene small: a few thousand messages for tens of thousands of lights.
  auto lights = CountSceneLights(proto, SceneLimits{}.lights);
  ASSERT_TRUE(lights.ok()) << lights.status();
  EXPECT_GE(*lights, 15000u);
  EXPECT_LT(*lights, SceneLimits{}.lights);
  EXPECT_LT(proto.lights_size() + proto.light_rows_size(), 2000);
  // The server's default polygon limit (aperture-server --max_scene_polygons).
  SceneBuildOptions options;
  options.limits.polygons = 4000000;
  auto scene = BuildScene(proto, options);
  ASSERT_TRUE(scene.ok()) << scene.status();
  EXPECT_EQ(scene->lights.lights.size(), *lights);
}

TEST(NightScene, ShowsFifteenThousandLightsAndTenThousandTexturedPolygons) {
  const Scene& scene = ClearNight();
  const Camera camera = NightCamera();
  const RenderSettings settings = FrameSettings(kWidth, kHeight);
  const FrameGeometry geometry = ProjectScene(scene, camera, kWidth, kHeight, 2);
  const std::vector<LightFootprint> footprints =
      ProjectLightPoints(scene, camera, geometry, settings);
  size_t on_screen = 0;
  for (const LightFootprint& f : footprints)
    on_screen += f.x >= 0 && f.x < kWidth && f.y >= 0 && f.y < kHeight;
  EXPECT_GE(on_screen, 15000u) << "of " << footprints.size() << " footprints";
  // Visible: of those, the ones that polygons in front (the town's houses) do not hide wholly.
  auto frame = RenderFrame(scene, camera, settings);
  ASSERT_TRUE(frame.ok()) << frame.status();
  EXPECT_GE(frame->stats.lights_drawn - frame->stats.lights_hidden, 15000u)
      << frame->stats.lights_hidden << " of " << frame->stats.lights_drawn << " hidden";
  size_t textured = 0;
  for (const ScreenPolygon& p : geometry.polygons)
    textured += scene.materials[p.material].texture >= 0;
  EXPECT_GE(textured, 10000u) << "of " << geometry.polygons.size() << " polygons in view";
}

TEST(NightScene, SixteenAircraftMoveWithTheirOwnLights) {
  const v1::Scene proto = MakeNightScene();
  const std::vector<std::string> aircraft = NightSceneAircraft();
  ASSERT_EQ(aircraft.size(), 16u);
  for (const std::string& name : aircraft) {
    int objects = 0;
    for (const v1::Object& o : proto.objects()) objects += o.name() == name;
    EXPECT_EQ(objects, 1) << name;
    int attached = 0, flashing = 0;
    for (const v1::LightPoint& light : proto.lights()) {
      if (light.object() != name) continue;
      ++attached;
      flashing += light.has_flash();
    }
    // Red, green and white navigation lights, two strobes and two beacons.
    EXPECT_GE(attached, 7) << name;
    EXPECT_GE(flashing, 4) << name;
  }
  int named = 0;
  for (const v1::Object& o : proto.objects()) named += !o.name().empty();
  EXPECT_EQ(named, 16);

  // Moving one moves its lights: the update that moves the lined-up aircraft 10 m to the east
  // moves the footprints of its lights (and only those) to the right, as far as it moves.
  auto scene = BuildScene(proto);
  ASSERT_TRUE(scene.ok()) << scene.status();
  const Camera camera = NightCamera();
  const RenderSettings settings = FrameSettings(kWidth, kHeight);
  auto footprints_of = [&](const Scene& s) {
    const FrameGeometry geometry = ProjectScene(s, camera, kWidth, kHeight, 2);
    return ProjectLightPoints(s, camera, geometry, settings);
  };
  const std::vector<LightFootprint> before = footprints_of(*scene);
  v1::SceneUpdate update;
  v1::ObjectUpdate& moved = *update.add_objects();
  moved.set_name(kDemoAircraft);
  for (const v1::Object& o : proto.objects())
    if (o.name() == kDemoAircraft) *moved.mutable_transform() = o.transform();
  const double x = moved.transform().translation().x();
  moved.mutable_transform()->mutable_translation()->set_x(x + 10);
  ASSERT_TRUE(ApplySceneUpdate(update, &*scene).ok());
  const std::vector<LightFootprint> after = footprints_of(*scene);
  ASSERT_EQ(before.size(), after.size());
  // 10 m across at the aircraft's distance, in pixels.
  const double distance = camera.position.z - 50;
  const double pixels = 10 / distance * (kHeight / 2.0) / std::tan(Radians(15));
  int changed = 0;
  for (size_t k = 0; k < before.size(); ++k) {
    if (before[k].x == after[k].x && before[k].y == after[k].y) continue;
    ++changed;
    EXPECT_NEAR(after[k].x - before[k].x, pixels, 0.2 * pixels);
    EXPECT_NEAR(after[k].y, before[k].y, 0.1);
  }
  EXPECT_GE(changed, 1);  // its tail light at least (the strobes may be off at time 0)
  EXPECT_LE(changed, 9);  // its own lights only
}

using testing::MapAt;

// The taxiways' lights were placed from the map's texels (AirportMapToWorld): nine in ten of
// their centre line lights stand on the map's paved taxiways (the rest where the measured centre
// lines cut a bend short); 60 m to the side, nearly all would stand on grass.
TEST(NightScene, TaxiwayLightsStandOnTheMapsTaxiways) {
  const Scene& scene = ClearNight();
  const auto group = scene.lights.group_index.find("taxiway-centre");
  ASSERT_NE(group, scene.lights.group_index.end());
  const Rgba grass{141 / 255.0f, 179 / 255.0f, 96 / 255.0f, 1};
  int on_grass = 0, lights = 0;
  for (const PointLight& light : scene.lights.lights) {
    if (light.group != static_cast<int>(group->second)) continue;
    ++lights;
    const Rgba c = MapAt(scene, light.position.x, light.position.z);
    on_grass += std::abs(c.r - grass.r) < 0.02f && std::abs(c.g - grass.g) < 0.02f &&
                std::abs(c.b - grass.b) < 0.02f;
  }
  ASSERT_GT(lights, 1000);
  EXPECT_LT(on_grass, lights / 10) << "of " << lights;
}

// Where a world point lands in a frame of `width` x `height` seen by `camera`.
Vec2 Project(const Camera& camera, int width, int height, const Vec3& world) {
  const FrustumTangents f = ResolveFrustum(camera, width, height);
  const Vec3 p = camera.Orientation().Transposed() * (world - camera.position);
  const double tx = p.x / -p.z, ty = p.y / -p.z;
  return {(tx - f.left) / (f.right - f.left) * width, (f.top - ty) / (f.top - f.bottom) * height};
}

// The brightest pixel within `radius` pixels of `at`, by its channels' sum.
Rgba BrightestNear(const Image& image, const Vec2& at, int radius) {
  Rgba best{0, 0, 0, 0};
  for (int y = static_cast<int>(at.y) - radius; y <= static_cast<int>(at.y) + radius; ++y)
    for (int x = static_cast<int>(at.x) - radius; x <= static_cast<int>(at.x) + radius; ++x) {
      if (x < 0 || y < 0 || x >= image.width() || y >= image.height()) continue;
      const Rgba& p = image.at(x, y);
      if (p.r + p.g + p.b > best.r + best.g + best.b) best = p;
    }
  return best;
}

// A small frame of the default view: the approach lights and the runway's lights shine where they
// project, the ground around them and the sky stay dark.
TEST(NightScene, ASmallFrameShowsTheRunwayLit) {
  auto builtin = FindBuiltinScene("night");
  ASSERT_TRUE(builtin.ok()) << builtin.status();
  auto scene = BuildScene(builtin->scene);
  ASSERT_TRUE(scene.ok()) << scene.status();
  // Small enough to be quick; every light is at least its minimum footprint, so the light pass
  // has the frame's whole crowd of footprints to resolve.
  constexpr int kSmallWidth = 320, kSmallHeight = 180;
  const Camera& camera = builtin->camera;
  auto frame = RenderFrame(*scene, camera, FrameSettings(kSmallWidth, kSmallHeight));
  ASSERT_TRUE(frame.ok()) << frame.status();
  const Image& image = frame->image;
  auto at = [&](const Vec3& world) { return Project(camera, kSmallWidth, kSmallHeight, world); };
  // The approach lights' centre line 450 m out, the threshold, the touchdown zone 400 m in (36L's
  // threshold at z = 200, landing along -z). At this size the threshold's green and the red side
  // rows share pixels; their colours are airport_lighting_test.cc's.
  for (const Vec3& lit : {Vec3{0, 1, 650}, Vec3{20, 0, 201}, Vec3{0, 0, -200}}) {
    const Rgba p = BrightestNear(image, at(lit), 1);
    EXPECT_GT(p.r + p.g + p.b, 1.0) << lit.z;
  }
  // The dark grass 150 m beside the approach lights, and the sky.
  const Rgba grass = BrightestNear(image, at({150, 0, 900}), 1);
  EXPECT_LT(grass.r + grass.g + grass.b, 0.1);
  for (int x = 0; x < kSmallWidth; ++x) {
    const Rgba& sky = image.at(x, 2);
    EXPECT_LT(sky.r + sky.g + sky.b, 0.05) << x;
  }
}

// The aircraft on the runways carry two landing lights and those taxiing a taxi light, spot lights
// on their objects within the budget; behind the lined-up aircraft the runway ahead of it is lit
// by its landing lights and dark with them switched off.
TEST(NightScene, LandingAndTaxiLightsLightTheRunwayAheadOfTheirAircraft) {
  const v1::Scene proto = MakeNightScene();
  ASSERT_LE(proto.spot_lights_size(), kMaxSpotLights);
  int landing = 0, taxi = 0;
  const std::vector<std::string> aircraft = NightSceneAircraft();
  for (const v1::SpotLight& s : proto.spot_lights()) {
    EXPECT_NE(std::find(aircraft.begin(), aircraft.end(), s.object()), aircraft.end())
        << s.object();
    landing += s.group() == kLandingLightGroup;
    taxi += s.group() == kTaxiLightGroup;
  }
  EXPECT_EQ(landing, 8);  // the lined-up, climbing, rolling-out and departing aircraft
  EXPECT_EQ(taxi, 7);     // the seven taxiing

  Scene scene = ClearNight();
  Camera behind;  // above and behind the aircraft lined up on 36L at z = 50, heading -z
  behind.position = {0, 60, 150};
  behind.pitch_deg = -25;
  constexpr int kSmallWidth = 320, kSmallHeight = 180;
  RenderSettings settings = FrameSettings(kSmallWidth, kSmallHeight);
  settings.draw_light_points = false;  // the ground alone
  auto lit = RenderFrame(scene, behind, settings);
  ASSERT_TRUE(lit.ok()) << lit.status();
  v1::SceneUpdate off;
  v1::LightGroupUpdate& g = *off.add_light_groups();
  g.set_group(kLandingLightGroup);
  g.set_visibility(v1::VISIBILITY_HIDDEN);
  ASSERT_TRUE(ApplySceneUpdate(off, &scene).ok());
  auto dark = RenderFrame(scene, behind, settings);
  ASSERT_TRUE(dark.ok()) << dark.status();
  // 32 m ahead of the lamps (x = +-4 m, z = 46.8 m), near their beams' axes, seen over the
  // aircraft's tail.
  for (const Vec3& ahead : {Vec3{-4, 0, 15}, Vec3{4, 0, 15}}) {
    const Vec2 at = Project(behind, kSmallWidth, kSmallHeight, ahead);
    const Rgba on = lit->image.at(static_cast<int>(at.x), static_cast<int>(at.y));
    const Rgba without = dark->image.at(static_cast<int>(at.x), static_cast<int>(at.y));
    EXPECT_GT(on.r, 0.02) << ahead.x;
    EXPECT_GT(on.r, 5 * without.r) << ahead.x;
  }
}

}  // namespace
}  // namespace aperture
