// The Annex 14 lighting generator (scene/airport_lighting.h): each system where chapter 5.3 puts
// it, in its colours, showing towards whom it should; the PAPI's four units read two white and two
// red on the slope; the sequenced flashers run one at a time from the outermost in; bad
// descriptions are refused naming the field, with nothing appended.
#include "scene/airport_lighting.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include "scene/light_points.h"

namespace aperture {
namespace {

// A category I runway 3,000 m x 45 m, its threshold at the origin, landing along -z.
RunwayDescription CatIRunway() {
  RunwayDescription r;
  r.designator = "36";
  r.threshold = {0, 0, 0};
  r.length_m = 3000;
  r.width_m = 45;
  r.category = RunwayCategory::kPrecisionCatI;
  return r;
}

SceneLights Lights(const v1::Scene& proto) {
  auto lights = BuildSceneLights(proto, {}, 0);
  EXPECT_TRUE(lights.ok()) << lights.status();
  return lights.ok() ? *std::move(lights) : SceneLights{};
}

std::vector<PointLight> InGroup(const SceneLights& lights, const std::string& group) {
  std::vector<PointLight> out;
  const auto it = lights.group_index.find(group);
  if (it == lights.group_index.end()) return out;
  for (const PointLight& light : lights.lights)
    if (light.group == static_cast<int>(it->second)) out.push_back(light);
  return out;
}

double Towards(const SceneLights& lights, const PointLight& light, const Vec3& eye,
               double time_s = 0) {
  return LightIntensityTowards(light, Normalize(eye - light.position), time_s, lights.groups);
}

bool IsRed(const PointLight& l) { return l.color.r > 3 * l.color.g && l.color.r > 3 * l.color.b; }
bool IsYellow(const PointLight& l) {
  return l.color.r > 1.2 * l.color.g && l.color.g > 4 * l.color.b;
}
bool IsWhite(const PointLight& l) { return l.color.b > 0.6 * l.color.r; }
bool IsGreen(const PointLight& l) { return l.color.g > 3 * l.color.r; }
bool IsBlue(const PointLight& l) { return l.color.b > 2 * l.color.g && l.color.b > 2 * l.color.r; }

// Annex 14 5.3.9: rows along both edges at most 60 m apart, the last 600 m yellow; their beams
// face the approach, while every way they show only the faint all-round part.
TEST(AirportLighting, EdgeLightsLineTheRunwayYellowOverTheLastSixHundredMetres) {
  v1::Scene scene;
  ASSERT_TRUE(AddRunwayLights(CatIRunway(), &scene).ok());
  const SceneLights lights = Lights(scene);
  const std::vector<PointLight> edge = InGroup(lights, kRunwayEdgeGroup);
  ASSERT_EQ(edge.size(), 2u * (3000 / 60 + 1));
  std::map<double, std::vector<double>> sides;  // lateral -> distances along
  for (const PointLight& l : edge) {
    EXPECT_NEAR(std::abs(l.position.x), 45.0 / 2 + 1, 1e-9);
    sides[l.position.x].push_back(-l.position.z);
    const double along = -l.position.z;
    if (along >= 3000 - 600 - 1e-6) {
      EXPECT_TRUE(IsYellow(l)) << along;
    } else {
      EXPECT_TRUE(IsWhite(l)) << along;
    }
    const double approach = Towards(lights, l, {0, 100, 2000});
    const double from_far_end = Towards(lights, l, {0, 20, -8000});
    EXPECT_GT(approach, 20 * from_far_end) << along;
    EXPECT_GT(from_far_end, 0) << "the all-round part, " << along;
  }
  ASSERT_EQ(sides.size(), 2u);
  for (auto& [lateral, along] : sides) {
    std::sort(along.begin(), along.end());
    EXPECT_NEAR(along.front(), 0, 1e-6);
    EXPECT_NEAR(along.back(), 3000, 1e-6);
    for (size_t k = 1; k < along.size(); ++k) EXPECT_LE(along[k] - along[k - 1], 60 + 1e-6);
  }
}

// Annex 14 5.3.10 and 5.3.11: green threshold lights at most 3 m apart across a precision runway,
// facing the approach; red end lights showing back along the runway (to the landing pilot, from
// the approach too), dark beyond the end.
TEST(AirportLighting, ThresholdIsGreenTowardsTheApproachAndTheEndRedTowardsTheRunway) {
  v1::Scene scene;
  ASSERT_TRUE(AddRunwayLights(CatIRunway(), &scene).ok());
  const SceneLights lights = Lights(scene);
  const std::vector<PointLight> threshold = InGroup(lights, kRunwayThresholdGroup);
  ASSERT_EQ(threshold.size(), 45u / 3 + 1);
  for (const PointLight& l : threshold) {
    EXPECT_TRUE(IsGreen(l));
    EXPECT_GT(Towards(lights, l, {0, 100, 2000}), 0);
  }
  const std::vector<PointLight> end = InGroup(lights, kRunwayEndGroup);
  ASSERT_GE(end.size(), 6u);
  for (const PointLight& l : end) {
    EXPECT_TRUE(IsRed(l));
    EXPECT_GT(Towards(lights, l, {0, 100, 2000}), 0);
    EXPECT_GT(Towards(lights, l, {0, 5, -1000}), 0);
    EXPECT_EQ(Towards(lights, l, {0, 20, -5000}), 0);
  }
}

// Annex 14 5.3.12: 15 m apart on a category III runway; white, then alternately red and white
// from 900 m before the end, then red over the last 300 m.
TEST(AirportLighting, CentreLineIsCodedRedTowardsTheEnd) {
  RunwayDescription runway = CatIRunway();
  runway.category = RunwayCategory::kPrecisionCatIII;
  v1::Scene scene;
  ASSERT_TRUE(AddRunwayLights(runway, &scene).ok());
  const SceneLights lights = Lights(scene);
  std::vector<PointLight> centre = InGroup(lights, kRunwayCentreGroup);
  std::sort(centre.begin(), centre.end(),
            [](const PointLight& a, const PointLight& b) { return a.position.z > b.position.z; });
  ASSERT_EQ(centre.size(), 3000u / 15 - 1);
  int coded_red = 0, coded_white = 0;
  for (size_t k = 0; k < centre.size(); ++k) {
    const PointLight& l = centre[k];
    const double to_end = 3000 + l.position.z;
    EXPECT_NEAR(l.position.x, 0, 1e-9);
    EXPECT_NEAR(-l.position.z, 15.0 * (k + 1), 1e-6);
    if (to_end <= 300 + 1e-6) {
      EXPECT_TRUE(IsRed(l)) << to_end;
    } else if (to_end <= 900 + 1e-6) {
      coded_red += IsRed(l);
      coded_white += IsWhite(l);
      if (k > 0 && 3000 + centre[k - 1].position.z <= 900 + 1e-6) {
        EXPECT_NE(IsRed(l), IsRed(centre[k - 1])) << "alternates, " << to_end;
      }
    } else {
      EXPECT_TRUE(IsWhite(l)) << to_end;
    }
  }
  EXPECT_EQ(coded_red, 20);
  EXPECT_EQ(coded_white, 20);
  // The touchdown zone's barrettes: 900 m of them, 30 m apart, three lights each side.
  EXPECT_EQ(InGroup(lights, kTouchdownZoneGroup).size(), 6u * 30);
}

// Annex 14 5.3.5: on the slope the four units show two white (the outer ones) and two red; a
// little high, three white; high, four; low, all red. Each unit shows one colour a tenth of a
// degree from its setting angle (2 deg 30', 2 deg 50', 3 deg 10', 3 deg 30' for 3 degrees).
TEST(AirportLighting, PapiShowsTwoWhiteTwoRedOnTheSlope) {
  RunwayDescription runway = CatIRunway();
  v1::Scene scene;
  ASSERT_TRUE(AddRunwayLights(runway, &scene).ok());
  const SceneLights lights = Lights(scene);
  const std::vector<PointLight> papi = InGroup(lights, kPapiGroup);
  ASSERT_EQ(papi.size(), 8u);  // four units, a white and a red light each
  // White units seen from `elevation_deg` above the PAPI's point, 3 km out on the approach.
  auto white_units = [&](double elevation_deg) {
    const Vec3 eye =
        Vec3{0, 0, -runway.papi_distance_m} +
        Vec3{0, std::sin(Radians(elevation_deg)), std::cos(Radians(elevation_deg))} * 3000.0;
    std::map<double, std::pair<double, double>> units;  // lateral -> (white, red)
    for (const PointLight& l : papi) {
      auto& unit = units[l.position.x];
      (IsRed(l) ? unit.second : unit.first) += Towards(lights, l, eye);
    }
    EXPECT_EQ(units.size(), 4u);
    int white = 0;
    for (const auto& [lateral, unit] : units) {
      EXPECT_TRUE(unit.first == 0 || unit.second == 0) << "one colour at " << elevation_deg;
      white += unit.first > unit.second;
    }
    return white;
  };
  EXPECT_EQ(white_units(3.0), 2);
  EXPECT_EQ(white_units(3.3), 3);
  EXPECT_EQ(white_units(3.7), 4);
  EXPECT_EQ(white_units(2.7), 1);
  EXPECT_EQ(white_units(2.3), 0);
  // On the left of the runway, the inner unit 15 m from its edge.
  double inner = -std::numeric_limits<double>::infinity();
  for (const PointLight& l : papi) {
    EXPECT_LT(l.position.x, 0);
    inner = std::max(inner, l.position.x);
  }
  EXPECT_NEAR(inner, -(45.0 / 2 + 15), 1e-9);
}

// Annex 14 5.3.4.20: the flashers fire in sequence from the outermost towards the threshold,
// twice a second, one at a time.
TEST(AirportLighting, ApproachFlashersRunInSequenceOneAtATime) {
  v1::Scene scene;
  ASSERT_TRUE(AddRunwayLights(CatIRunway(), &scene).ok());
  const SceneLights lights = Lights(scene);
  const std::vector<PointLight> flashers = InGroup(lights, kApproachFlasherGroup);
  ASSERT_EQ(flashers.size(), 30u);
  const Vec3 eye{0, 150, 3000};
  double last_on = std::numeric_limits<double>::infinity();
  for (int step = 0; step < 50; ++step) {
    const double t = 0.01 * step + 0.005;  // within one 0.5 s sweep
    int on = 0;
    double at = 0;
    for (const PointLight& l : flashers) {
      if (Towards(lights, l, eye, t) > 0) {
        ++on;
        at = l.position.z;
      }
    }
    ASSERT_EQ(on, 1) << "t " << t;
    EXPECT_LE(at, last_on) << "t " << t;  // moving in, towards the threshold at z = 0
    last_on = at;
  }
  EXPECT_NEAR(last_on, 30, 1e-6);
  // The steady approach lights: barrettes of five on the centre line out to 900 m, crossbar at 300.
  const std::vector<PointLight> approach = InGroup(lights, kApproachGroup);
  double farthest = 0;
  for (const PointLight& l : approach) {
    EXPECT_TRUE(IsWhite(l));
    farthest = std::max(farthest, l.position.z);
  }
  EXPECT_NEAR(farthest, 900, 1e-6);
  EXPECT_EQ(approach.size(), 5u * 30 + 2 * 8);
}

TEST(AirportLighting, BrightnessStepDimsEverySystem) {
  v1::Scene full, dimmed;
  RunwayDescription runway = CatIRunway();
  ASSERT_TRUE(AddRunwayLights(runway, &full).ok());
  runway.intensity_scale = 0.05;
  ASSERT_TRUE(AddRunwayLights(runway, &dimmed).ok());
  ASSERT_EQ(full.lights_size(), dimmed.lights_size());
  ASSERT_EQ(full.light_rows_size(), dimmed.light_rows_size());
  for (int i = 0; i < full.lights_size(); ++i)
    EXPECT_NEAR(dimmed.lights(i).intensity_cd(), 0.05 * full.lights(i).intensity_cd(),
                1e-9 * full.lights(i).intensity_cd());
  for (int i = 0; i < full.light_rows_size(); ++i)
    EXPECT_NEAR(dimmed.light_rows(i).light().intensity_cd(),
                0.05 * full.light_rows(i).light().intensity_cd(),
                1e-9 * full.light_rows(i).light().intensity_cd());
}

TEST(AirportLighting, BadRunwaysAreRefusedNamingTheFieldAndAppendNothing) {
  struct Case {
    const char* field;
    void (*spoil)(RunwayDescription&);
  };
  const Case cases[] = {
      {"designator", [](RunwayDescription& r) { r.designator = "37"; }},
      {"designator", [](RunwayDescription& r) { r.designator = "09X"; }},
      {"threshold", [](RunwayDescription& r) { r.threshold.y = std::nan(""); }},
      {"heading_deg", [](RunwayDescription& r) { r.heading_deg = INFINITY; }},
      {"length_m", [](RunwayDescription& r) { r.length_m = 0; }},
      {"width_m", [](RunwayDescription& r) { r.width_m = -45; }},
      {"approach_slope_deg", [](RunwayDescription& r) { r.approach_slope_deg = 12; }},
      {"papi_distance_m", [](RunwayDescription& r) { r.papi_distance_m = 3000; }},
      {"intensity_scale", [](RunwayDescription& r) { r.intensity_scale = 0; }},
      {"intensity_scale", [](RunwayDescription& r) { r.intensity_scale = 1.5; }},
  };
  for (const Case& c : cases) {
    RunwayDescription runway = CatIRunway();
    c.spoil(runway);
    v1::Scene scene;
    const absl::Status status = AddRunwayLights(runway, &scene);
    EXPECT_EQ(status.code(), absl::StatusCode::kInvalidArgument) << c.field;
    EXPECT_NE(status.message().find(c.field), std::string::npos) << status;
    EXPECT_EQ(scene.lights_size() + scene.light_rows_size(), 0) << c.field;
  }
}

// Annex 14 5.3.17, 5.3.18 and 5.3.20: green centre line lights at most the spacing apart (closer
// near a turn), blue edge lights every way, and a red stop bar across the taxiway facing the
// traffic that comes along it.
TEST(AirportLighting, TaxiwayCentreLineEdgesAndStopBar) {
  TaxiwayDescription taxiway;
  taxiway.name = "A";
  taxiway.centre_line = {{0, 0, 0}, {0, 0, -300}, {200, 0, -300}};
  taxiway.centre_spacing_m = 15;
  taxiway.stop_bars_m = {100};
  v1::Scene scene;
  ASSERT_TRUE(AddTaxiwayLights(taxiway, &scene).ok());
  const SceneLights lights = Lights(scene);
  const std::vector<PointLight> centre = InGroup(lights, kTaxiwayCentreGroup);
  ASSERT_FALSE(centre.empty());
  std::vector<double> first_leg;  // distances along the first leg, each fitting once
  for (const PointLight& l : centre) {
    EXPECT_TRUE(IsGreen(l));
    const bool on_first = std::abs(l.position.x) < 1e-9;
    const bool on_second = std::abs(l.position.z + 300) < 1e-9;
    EXPECT_TRUE(on_first || on_second) << l.position.x << ", " << l.position.z;
    if (on_first) first_leg.push_back(-l.position.z);
  }
  std::sort(first_leg.begin(), first_leg.end());
  first_leg.erase(std::unique(first_leg.begin(), first_leg.end(),
                              [](double a, double b) { return std::abs(a - b) < 1e-6; }),
                  first_leg.end());
  for (size_t k = 1; k < first_leg.size(); ++k)
    EXPECT_LE(first_leg[k] - first_leg[k - 1], 7.5 + 1e-6);  // the leg ends in a turn: halved
  for (const PointLight& l : InGroup(lights, kTaxiwayEdgeGroup)) {
    EXPECT_TRUE(IsBlue(l));
    EXPECT_FALSE(l.directional);
  }
  const std::vector<PointLight> bar = InGroup(lights, kStopBarGroup);
  ASSERT_GE(bar.size(), 23u / 3 + 1);
  for (const PointLight& l : bar) {
    EXPECT_TRUE(IsRed(l));
    EXPECT_NEAR(l.position.z, -100, 1e-6);
    EXPECT_GT(Towards(lights, l, {0, 3, 0}), 0) << "towards the traffic";
    EXPECT_EQ(Towards(lights, l, {0, 3, -200}), 0) << "not past the bar";
  }
}

TEST(AirportLighting, BadTaxiwaysAreRefusedNamingTheField) {
  TaxiwayDescription taxiway;
  taxiway.name = "B";
  taxiway.centre_line = {{0, 0, 0}};
  v1::Scene scene;
  absl::Status status = AddTaxiwayLights(taxiway, &scene);
  EXPECT_NE(status.message().find("taxiway 'B' centre_line"), std::string::npos) << status;
  taxiway.centre_line = {{0, 0, 0}, {0, 0, 0}, {10, 0, 0}};
  status = AddTaxiwayLights(taxiway, &scene);
  EXPECT_NE(status.message().find("centre_line[1]"), std::string::npos) << status;
  taxiway.centre_line = {{0, 0, 0}, {0, 0, -100}};
  taxiway.stop_bars_m = {150};
  status = AddTaxiwayLights(taxiway, &scene);
  EXPECT_NE(status.message().find("stop_bars_m[0]"), std::string::npos) << status;
  EXPECT_EQ(scene.lights_size() + scene.light_rows_size(), 0);
}

// Annex 14 chapter 6: steady red low-intensity lights on lower structures, flashing red
// medium-intensity ones from 45 m up.
TEST(AirportLighting, ObstacleLightsByHeight) {
  v1::Scene scene;
  ASSERT_TRUE(AddObstacleLights({{0, 20, 0}}, 20, &scene).ok());
  ASSERT_TRUE(AddObstacleLights({{50, 60, 0}}, 60, &scene).ok());
  ASSERT_EQ(scene.lights_size(), 2);
  EXPECT_FALSE(scene.lights(0).has_flash());
  EXPECT_GE(scene.lights(0).intensity_cd(), 32);
  EXPECT_TRUE(scene.lights(1).has_flash());
  EXPECT_GE(scene.lights(1).intensity_cd(), 2000);
  EXPECT_FALSE(AddObstacleLights({{0, 0, 0}}, 0, &scene).ok());
  const absl::Status bad = AddObstacleLights({{0, std::nan(""), 0}}, 20, &scene);
  EXPECT_NE(bad.message().find("positions[0]"), std::string::npos) << bad;
}

}  // namespace
}  // namespace aperture
