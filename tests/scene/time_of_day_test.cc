// A scene's time of day: built from the proto, set per frame by a SceneUpdate (the same scene as a
// fresh load at that hour), and bad values refused naming the field.
#include <gtest/gtest.h>

#include <cstring>
#include <string>

#include "scene/airport_scene.h"
#include "scene/demo_scene.h"
#include "scene/scene_builder.h"
#include "scene/scene_update.h"

namespace aperture {
namespace {

bool SameRgba(const Rgba& a, const Rgba& b) { return std::memcmp(&a, &b, sizeof(Rgba)) == 0; }

void ExpectSameLight(const Scene& a, const Scene& b) {
  EXPECT_TRUE(a.sun_direction == b.sun_direction);
  EXPECT_TRUE(SameRgba(a.sun_color, b.sun_color));
  EXPECT_TRUE(SameRgba(a.ambient, b.ambient));
  EXPECT_TRUE(SameRgba(a.sky, b.sky));
  EXPECT_TRUE(SameRgba(a.fog_color, b.fog_color));
  EXPECT_EQ(a.fog_density, b.fog_density);
  EXPECT_EQ(a.sky_dome.analytic, b.sky_dome.analytic);
  EXPECT_TRUE(SameRgba(a.sky_dome.scale, b.sky_dome.scale));
  for (const Vec3& d : {Vec3{0, 1, 0}, Vec3{0.6, 0.2, -0.77}, Vec3{-1, 0, 0}})
    EXPECT_TRUE(SameRgba(a.sky_dome.Radiance(d), b.sky_dome.Radiance(d)));
}

v1::Scene DemoAt(const std::string& utc) {
  v1::Scene proto = MakeDemoScene();
  v1::TimeOfDay& t = *proto.mutable_time_of_day();
  t.set_utc(utc);
  t.mutable_place()->set_latitude_deg(52.31);
  t.mutable_place()->set_longitude_deg(4.76);
  return proto;
}

TEST(TimeOfDay, ReplacesTheScenesSunAmbientAndSky) {
  auto plain = BuildScene(MakeDemoScene());
  auto noon = BuildScene(DemoAt("2026-06-21T12:00Z"));
  ASSERT_TRUE(plain.ok() && noon.ok()) << noon.status();
  EXPECT_FALSE(plain->sky_dome.analytic);
  EXPECT_TRUE(noon->sky_dome.analytic);
  EXPECT_FALSE(noon->sun_direction == plain->sun_direction);
  EXPECT_GT(noon->sun_direction.y, 0.8);             // 61 degrees up
  EXPECT_EQ(noon->fog_density, plain->fog_density);  // the scene's fog density stays
}

TEST(TimeOfDay, PerFrameUpdateEqualsAFreshLoad) {
  auto noon = BuildScene(DemoAt("2026-06-21T12:00Z"));
  auto dusk = BuildScene(DemoAt("2026-06-21T20:27Z"));
  ASSERT_TRUE(noon.ok() && dusk.ok());
  v1::SceneUpdate update;
  update.mutable_time_of_day()->set_utc("2026-06-21T20:27Z");  // the place is the scene's
  ASSERT_TRUE(ApplySceneUpdate(update, &*noon).ok());
  ExpectSameLight(*noon, *dusk);

  // An update's sun or sky does not outlive the hour: the time of day wins, as in a fresh load.
  v1::SceneUpdate sun;
  sun.mutable_sun()->mutable_direction()->set_y(1);
  sun.mutable_sky()->set_b(1);
  ASSERT_TRUE(ApplySceneUpdate(sun, &*noon).ok());
  ExpectSameLight(*noon, *dusk);

  // Merged updates of skipped frames make the same scene as applying them in turn.
  auto a = BuildScene(DemoAt("2026-06-21T12:00Z"));
  auto b = BuildScene(DemoAt("2026-06-21T12:00Z"));
  v1::SceneUpdate first, second;
  first.mutable_time_of_day()->set_utc("2026-06-21T18:00Z");
  second.mutable_time_of_day()->mutable_place()->set_latitude_deg(40);
  second.mutable_time_of_day()->mutable_place()->set_longitude_deg(-3);
  ASSERT_TRUE(ApplySceneUpdate(first, &*a).ok());
  ASSERT_TRUE(ApplySceneUpdate(second, &*a).ok());
  MergeSceneUpdate(second, &first);
  ASSERT_TRUE(ApplySceneUpdate(first, &*b).ok());
  ExpectSameLight(*a, *b);
}

TEST(TimeOfDay, TheAirportHasSchipholsPlaceAndTakesTheHourFromAnUpdate) {
  auto airport = BuildScene(MakeAirportScene());
  ASSERT_TRUE(airport.ok()) << airport.status();
  ASSERT_TRUE(airport->time_of_day.has_value());
  EXPECT_EQ(airport->time_of_day->place.latitude_deg, 52.31);
  EXPECT_EQ(airport->time_of_day->place.longitude_deg, 4.76);
  EXPECT_FALSE(airport->sky_dome.analytic);  // no hour yet: the scene's own sky
  v1::SceneUpdate update;
  update.mutable_time_of_day()->set_utc("2026-06-21T12:00Z");
  ASSERT_TRUE(ApplySceneUpdate(update, &*airport).ok());
  EXPECT_TRUE(airport->sky_dome.analytic);
}

// The error of building `proto`, or of applying `update` to the demo at noon.
std::string BuildError(const v1::Scene& proto) {
  auto scene = BuildScene(proto);
  return scene.ok() ? "" : std::string(scene.status().message());
}
std::string UpdateError(const v1::SceneUpdate& update, const v1::Scene& proto) {
  auto scene = BuildScene(proto);
  if (!scene.ok()) return "build failed";
  const absl::Status s = ApplySceneUpdate(update, &*scene);
  return s.ok() ? "" : std::string(s.message());
}

TEST(TimeOfDay, RefusesBadInputNamingTheField) {
  v1::Scene proto = DemoAt("2026-06-21T12:00Z");
  proto.mutable_time_of_day()->mutable_place()->set_latitude_deg(95);
  EXPECT_NE(BuildError(proto).find("time_of_day.place.latitude_deg"), std::string::npos)
      << BuildError(proto);
  proto = DemoAt("noon");
  EXPECT_NE(BuildError(proto).find("time_of_day.utc"), std::string::npos) << BuildError(proto);
  proto = DemoAt("2026-06-21T12:00Z");
  proto.mutable_time_of_day()->set_turbidity(40);
  EXPECT_NE(BuildError(proto).find("time_of_day.turbidity"), std::string::npos);
  proto = DemoAt("2026-06-21T12:00Z");
  proto.mutable_time_of_day()->clear_place();
  EXPECT_NE(BuildError(proto).find("time_of_day.place"), std::string::npos);

  v1::SceneUpdate update;
  update.mutable_time_of_day()->set_utc("21 June 2026");
  EXPECT_NE(UpdateError(update, DemoAt("2026-06-21T12:00Z")).find("update.time_of_day.utc"),
            std::string::npos);
  update.mutable_time_of_day()->set_utc("2026-06-21T12:00Z");
  update.mutable_time_of_day()->mutable_place()->set_latitude_deg(-95);
  EXPECT_NE(UpdateError(update, DemoAt("2026-06-21T12:00Z"))
                .find("update.time_of_day.place.latitude_deg"),
            std::string::npos);
  // A scene without a place takes an hour only with one.
  v1::SceneUpdate hour_only;
  hour_only.mutable_time_of_day()->set_utc("2026-06-21T12:00Z");
  EXPECT_NE(UpdateError(hour_only, MakeDemoScene()).find("update.time_of_day.place"),
            std::string::npos);
  // A refused update changes nothing.
  auto scene = BuildScene(DemoAt("2026-06-21T12:00Z"));
  auto fresh = BuildScene(DemoAt("2026-06-21T12:00Z"));
  ASSERT_TRUE(scene.ok() && fresh.ok());
  EXPECT_FALSE(ApplySceneUpdate(update, &*scene).ok());
  ExpectSameLight(*scene, *fresh);
}

}  // namespace
}  // namespace aperture
