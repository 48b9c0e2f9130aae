#include "scene/night_scene.h"

#include <cmath>
#include <utility>

#include "scene/aircraft_lights.h"
#include "scene/airport_lighting.h"
#include "scene/airport_map.h"
#include "scene/airport_runways.h"
#include "scene/airport_scene.h"
#include "scene/approach_camera.h"
#include "scene/demo_geometry.h"
#include "scene/demo_scene.h"
#include "scene/night_town.h"

namespace aperture {
namespace {

using demo::SetColor;

// The runways' brightness step: step 3 of five (5 % of full intensity). FAA Order JO 7110.65,
// Table 3-4-8, has the tower select it at night for visibilities of 1 to 3 miles, and the lower
// steps beyond; step 3 keeps the runway the brightest thing in a frame that also shows a town.
constexpr double kNightStep = 0.05;

// The light group of the apron's floodlight masts.
constexpr char kApronFloodlightGroup[] = "apron-floodlights";

// A taxiway read off the map: its centre line's texels, from the apron end to the runway end, and
// the indices of the points where stop bars stand.
struct MapTaxiway {
  const char* name;
  std::vector<std::pair<double, double>> texels;
  std::vector<size_t> stop_bars_at;
};

TaxiwayDescription ToTaxiway(const MapTaxiway& map) {
  TaxiwayDescription t;
  t.name = map.name;
  t.width_m = 23;
  t.centre_spacing_m = 15;
  double along = 0;
  for (size_t i = 0; i < map.texels.size(); ++i) {
    const Vec3 p = AirportMapToWorld(map.texels[i].first, map.texels[i].second);
    if (i > 0) along += Length(p - t.centre_line.back());
    t.centre_line.push_back(p);
    for (size_t at : map.stop_bars_at)
      if (at == i) t.stop_bars_m.push_back(along);
  }
  return t;
}

// The Polderbaan's taxiways east of it, and those west of 36C, measured on the map's 8192 texels.
std::vector<MapTaxiway> NightTaxiways() {
  return {
      {"Z",
       {{2580, 4700},
        {2090, 4170},
        {1900, 4000},
        {1700, 3820},
        {1620, 3755},
        {1570, 3712},
        {1510, 3697},
        {1440, 3732}},
       {}},
      {"A",
       {{1440, 3732},
        {1420, 3750},
        {1245, 3950},
        {1215, 3970},
        {1172, 3985},
        {1140, 3985},
        {1118, 3975}},
       {4}},
      {"B",
       {{1440, 3732},
        {1300, 3610},
        {1292, 3570},
        {1297, 3290},
        {1312, 3150},
        {1326, 2850},
        {1330, 2760},
        {1315, 2705},
        {1255, 2585},
        {1225, 2500},
        {1207, 2432}},
       {8}},
      {"B3", {{1300, 3610}, {1250, 3570}, {1200, 3530}, {1152, 3470}}, {2}},
      {"B5", {{1300, 3280}, {1278, 3200}, {1236, 3122}, {1200, 3050}, {1174, 2980}}, {2}},
      {"W", {{2640, 4700}, {2676, 4640}, {2700, 4200}, {2730, 3700}}, {}},
      {"V", {{2600, 4740}, {2640, 4790}, {2880, 4796}, {2904, 4796}}, {2}},
  };
}

// A named aircraft: the demo's twin-jet mesh, where and how it stands.
struct NightAircraft {
  const char* name;
  Vec3 at;
  double yaw_deg, pitch_deg, scale;
  AircraftBeams beams;
};

// The yaw of travel from texel a to texel b on the map.
double MapYaw(double ax, double ay, double bx, double by) {
  const Vec3 d = AirportMapToWorld(bx, by) - AirportMapToWorld(ax, ay);
  return std::atan2(-d.x, -d.z) * 180 / kPi;
}

// Where an aircraft taxiing from texel a towards texel b stands, a fraction `t` of the way.
Vec3 OnMap(double ax, double ay, double bx, double by, double t) {
  const Vec3 a = AirportMapToWorld(ax, ay), b = AirportMapToWorld(bx, by);
  Vec3 p = a + (b - a) * t;
  p.y = 0.15;
  return p;
}

constexpr AircraftBeams kLandingLights{.landing = true}, kTaxiing{.taxi = true};

std::vector<NightAircraft> Aircraft() {
  const Vec3 c36_south = AirportMapToWorld(k36CSouthX, k36CSouthY);
  const Vec3 c36_north = AirportMapToWorld(k36CNorthX, k36CNorthY);
  const double c36_yaw = MapYaw(k36CSouthX, k36CSouthY, k36CNorthX, k36CNorthY);
  auto on_36c = [&](double t) {
    Vec3 p = c36_south + (c36_north - c36_south) * t;
    p.y = 0.15;
    return p;
  };
  return {
      // Lined up on 36L where the demo puts it (DemoAircraftAt(0)), its landing lights on for the
      // take-off: they light the runway ahead of it.
      {kDemoAircraft, {0, 0.15, 50}, 0, 0, 1, kLandingLights},
      // Climbing out of 36L ahead of the camera, its landing lights still on.
      {"climb-out", {0, 150, -2900}, 0, 8, 1, kLandingLights},
      // Rolling out after landing, its landing lights on the runway ahead.
      {"rollout", {0, 0.15, -1900}, 0, 0, 1, kLandingLights},
      {"taxi-b1", OnMap(1297, 3290, 1297, 3570, 0.3), MapYaw(1297, 3290, 1297, 3570), 0, 1,
       kTaxiing},
      {"taxi-b2", OnMap(1326, 2850, 1312, 3150, 0.2), MapYaw(1326, 2850, 1312, 3150), 0, 0.8,
       kTaxiing},
      {"taxi-z1", OnMap(2090, 4170, 1900, 4000, 0.5), MapYaw(2090, 4170, 1900, 4000), 0, 1,
       kTaxiing},
      {"taxi-a1", OnMap(1245, 3950, 1215, 3970, 0.2), MapYaw(1245, 3950, 1215, 3970), 0, 0.8,
       kTaxiing},
      {"taxi-z2", OnMap(1900, 4000, 2090, 4170, 0.8), MapYaw(1900, 4000, 2090, 4170), 0, 1.2,
       kTaxiing},
      {"stand-1", {-196, 0.15, -130}, -90, 0, 1, {}},
      {"stand-2", {-196, 0.15, -220}, -90, 0, 1.1, {}},
      {"stand-3", {-196, 0.15, -310}, -90, 0, 0.8, {}},
      {"stand-4", {-196, 0.15, -400}, -90, 0, 1, {}},
      {"departure-36c", on_36c(0.15), c36_yaw, 0, 1, kLandingLights},
      {"rollout-36c", on_36c(0.55), c36_yaw, 0, 1.1, {}},
      {"taxi-w1", OnMap(2700, 4200, 2730, 3700, 0.4), MapYaw(2700, 4200, 2730, 3700), 0, 1,
       kTaxiing},
      {"taxi-v1", OnMap(2600, 4740, 2880, 4796, 0.6), MapYaw(2640, 4790, 2880, 4796), 0, 0.9,
       kTaxiing},
  };
}

void SetVec(v1::Vec3* out, const Vec3& v) {
  out->set_x(v.x);
  out->set_y(v.y);
  out->set_z(v.z);
}

// A clear, moonlit night: a dark sky, starlight and a little sky glow as ambient, a low moon for
// the sun. No haze: the air is clear (a hazy night's fog would also give every light a halo, a
// second footprint).
void SetNight(v1::Scene& scene) {
  SetColor(scene.mutable_sky(), 0.004f, 0.006f, 0.014f);
  SetColor(scene.mutable_ambient(), 0.006f, 0.006f, 0.009f);
  scene.mutable_sun()->mutable_direction()->set_x(-0.3);
  scene.mutable_sun()->mutable_direction()->set_y(0.6);
  scene.mutable_sun()->mutable_direction()->set_z(-0.5);
  SetColor(scene.mutable_sun()->mutable_color(), 0.012f, 0.014f, 0.02f);
  scene.clear_fog();
  scene.mutable_light_settings()->set_exposure(0.01);
  // The ground under the aircraft's landing and taxi lights as a night-adapted eye sees it: a
  // white surface under 1 lux is 0.03.
  scene.mutable_light_settings()->set_surface_exposure(10);
}

// An apron in front of the hangars (their aircraft stands), floodlit from masts along its east
// side: three 2,500 cd lamps 25 m up on each.
void AddApron(v1::Scene& scene) {
  v1::Mesh* apron = scene.add_meshes();
  apron->set_id("apron");
  apron->set_material_id("concrete");
  demo::AddFlatRect(apron, -229, -470, -152, -60, 0.02);
  scene.add_objects()->set_mesh_id("apron");
  for (double z = -85; z >= -445; z -= 90) {
    for (double dx : {-0.6, 0.0, 0.6}) {
      v1::LightPoint* lamp = scene.add_lights();
      SetVec(lamp->mutable_position(), {-154 + dx, 25, z});
      SetColor(lamp->mutable_color(), 1.05f, 0.98f, 0.80f);
      lamp->set_intensity_cd(2500);
      lamp->set_group(kApronFloodlightGroup);
      lamp->set_radius_m(0.3);
    }
  }
}

v1::Scene BuildNightScene() {
  v1::Scene scene = MakeAirportScene();
  scene.set_name("airport-night");
  SetNight(scene);

  // The runways' lights (scene/airport_runways.h).
  RunwayDescription polderbaan = Polderbaan36L();
  polderbaan.intensity_scale = kNightStep;
  RunwayDescription zwanenburgbaan = Zwanenburgbaan36C();
  zwanenburgbaan.intensity_scale = kNightStep;
  // The built-in data is known good: a failure here is a programming error the tests catch.
  for (const RunwayDescription& runway : {polderbaan, zwanenburgbaan})
    if (!AddRunwayLights(runway, &scene).ok()) return {};
  for (const MapTaxiway& taxiway : NightTaxiways())
    if (!AddTaxiwayLights(ToTaxiway(taxiway), &scene).ok()) return {};
  // The tower's cab roof (41 m) and the hangars' roofs (18 m) carry low-intensity obstacle lights.
  if (!AddObstacleLights({{-216.3, 41.3, -626.3},
                          {-203.7, 41.3, -626.3},
                          {-216.3, 41.3, -613.7},
                          {-203.7, 41.3, -613.7}},
                         41, &scene)
           .ok())
    return {};
  for (int i = 0; i < 4; ++i)
    if (!AddObstacleLights({{-290.2, 18.3, -160.2 - i * 90}, {-229.8, 18.3, -100.0 - i * 90}}, 18,
                           &scene)
             .ok())
      return {};
  AddApron(scene);

  // The town: west of the runway (clear of the hangars, the tower and the trees), and on both
  // sides of the approach, east of it up to taxiway Z and runway 36C; a motorway crosses under the
  // approach 1,400 m before the threshold.
  AddTownMaterials(&scene);
  constexpr double kMotorwayZ = 1600, kMotorwayHalfWidth = 40;
  constexpr double kSouth = kMotorwayZ + kMotorwayHalfWidth,
                   kNorth = kMotorwayZ - kMotorwayHalfWidth;
  const TownDistrict districts[] = {
      {"town-west", -4000, -4200, -480, 300, -1900, -1500, 1300, 5},
      {"town-south-west", -2600, 300, -260, kNorth, -1300, 1000, 800, 11},
      {"town-south-west-2", -2600, kSouth, -260, 3700, -1400, 2600, 700, 13},
      {"town-east", 300, 400, 1050, kNorth, 700, 1100, 500, 23},
      {"town-far-east", 1050, 1100, 1950, kNorth, 1500, 1300, 400, 29},
      {"town-south-east", 300, kSouth, 1950, 3700, 1100, 2600, 600, 31},
  };
  for (const TownDistrict& district : districts) AddTownDistrict(district, &scene);
  AddMotorway({"motorway", -4000, 2000, kMotorwayZ, 30}, &scene);

  // The aircraft: the airport already places the demo's; 15 more share its mesh.
  int index = 0;
  for (const NightAircraft& a : Aircraft()) {
    v1::Object* object = nullptr;
    for (v1::Object& o : *scene.mutable_objects())
      if (o.name() == a.name) object = &o;
    if (object == nullptr) {
      object = scene.add_objects();
      object->set_mesh_id("aircraft");
      object->set_name(a.name);
    }
    v1::Transform& t = *object->mutable_transform();
    SetVec(t.mutable_translation(), a.at);
    t.set_yaw_deg(a.yaw_deg);
    t.set_pitch_deg(a.pitch_deg);
    if (a.scale != 1) SetVec(t.mutable_scale(), {a.scale, a.scale, a.scale});
    // Out of step: at scene time 0 the strobes of a third of them are on, the beacons of another.
    AddAircraftLights(a.name, -0.4 * (index % 3) - 0.02, a.beams, &scene);
    ++index;
  }
  return scene;
}

}  // namespace

v1::Scene MakeNightScene() {
  static const v1::Scene* const night = new v1::Scene(BuildNightScene());
  return *night;
}

v1::Scene MakeNightSceneByDay() {
  v1::Scene scene = MakeNightScene();
  const v1::Scene day = MakeAirportScene();
  scene.set_name("airport-night-by-day");
  *scene.mutable_sky() = day.sky();
  *scene.mutable_ambient() = day.ambient();
  *scene.mutable_sun() = day.sun();
  *scene.mutable_fog() = day.fog();
  scene.clear_lights();
  scene.clear_light_rows();
  scene.clear_spot_lights();
  scene.clear_light_settings();
  return scene;
}

Camera NightCamera() {
  // 1 NM out on 36L's 3 degree path (through the PAPI's 300 m point).
  return ApproachCamera(Polderbaan36L(), 1852, -4, 30);
}

std::vector<std::string> NightSceneAircraft() {
  std::vector<std::string> names;
  for (const NightAircraft& a : Aircraft()) names.push_back(a.name);
  return names;
}

}  // namespace aperture
