#include "scene/aircraft_lights.h"

#include <cmath>

#include "scene/vec.h"

namespace aperture {
namespace {

void SetVec(v1::Vec3* out, const Vec3& v) {
  out->set_x(v.x);
  out->set_y(v.y);
  out->set_z(v.z);
}

// A light on `object` at `at` (its frame), of a linear colour scaled to luminance 1.
v1::LightPoint* AddLight(v1::Scene* scene, const std::string& object, const char* group,
                         const Vec3& at, double r, double g, double b, double cd) {
  v1::LightPoint* p = scene->add_lights();
  SetVec(p->mutable_position(), at);
  const double luminance = 0.2126 * r + 0.7152 * g + 0.0722 * b;
  p->mutable_color()->set_r(static_cast<float>(r / luminance));
  p->mutable_color()->set_g(static_cast<float>(g / luminance));
  p->mutable_color()->set_b(static_cast<float>(b / luminance));
  p->set_intensity_cd(cd);
  p->set_group(group);
  p->set_object(object);
  p->set_radius_m(0.15);
  return p;
}

void SetLobe(v1::LightPoint* p, const Vec3& axis, double horizontal_deg, double vertical_deg) {
  SetVec(p->mutable_lobe()->mutable_axis(), Normalize(axis));
  p->mutable_lobe()->set_horizontal_deg(horizontal_deg);
  p->mutable_lobe()->set_vertical_deg(vertical_deg);
}

void SetFlash(v1::LightPoint* p, double period_s, double on_s, double phase_s) {
  p->mutable_flash()->set_period_s(period_s);
  p->mutable_flash()->set_on_s(on_s);
  p->mutable_flash()->set_phase_s(phase_s);
}

// A warm white spot light on `object` at `at` (its frame), aimed ahead (-z) `down_deg` below the
// horizontal.
void AddSpot(v1::Scene* scene, const std::string& object, const char* group, const Vec3& at,
             double down_deg, double cd, double inner_deg, double outer_deg) {
  v1::SpotLight* s = scene->add_spot_lights();
  SetVec(s->mutable_position(), at);
  SetVec(s->mutable_direction(), {0, -std::sin(Radians(down_deg)), -std::cos(Radians(down_deg))});
  s->set_object(object);
  s->set_group(group);
  s->set_intensity_cd(cd);
  s->set_inner_deg(inner_deg);
  s->set_outer_deg(outer_deg);
  // 1, 0.95, 0.85 scaled to luminance 1, as the other lamps' colours.
  s->mutable_color()->set_r(1.0f / 0.95341f);
  s->mutable_color()->set_g(0.95f / 0.95341f);
  s->mutable_color()->set_b(0.85f / 0.95341f);
  s->set_radius_m(0.15);
}

}  // namespace

// 14 CFR 25.1385-25.1401: the forward navigation lights cover 110 degrees from dead ahead to
// their side, at least 40 cd near ahead falling to 5 cd at the side (here a 50 cd lobe aimed 50
// degrees out, 70 degrees wide, 60 % of it at 110 degrees); the rear light 140 degrees aft, at
// least 20 cd (30 cd); anti-collision lights flash 40 to 100 times a minute with at least 400 cd
// effective (strobes 1,500 cd 50 times a minute, the beacon 400 cd 60 times). Landing lights:
// 200,000 cd, a typical sealed-beam lamp, full within 5 degrees of its axis and ending at 11,
// aimed 4 degrees down (on the ground its pool runs from about 10 m ahead to the horizon, brightest
// 20 to 60 m ahead); the taxi light 40,000 cd, full within 10 degrees and ending at 24, aimed
// 6 degrees down so that it lights the taxiway from a few metres ahead of the nose gear.
void AddAircraftLights(const std::string& object, double phase_s, AircraftBeams beams,
                       v1::Scene* scene) {
  const double out = std::sin(Radians(50)), ahead = -std::cos(Radians(50));
  SetLobe(AddLight(scene, object, kNavigationLightGroup, {-17.2, 2.6, -2.5}, 1, 0.04, 0.02, 50),
          {-out, 0, ahead}, 70, 75);
  SetLobe(AddLight(scene, object, kNavigationLightGroup, {17.2, 2.6, -2.5}, 0.05, 1, 0.45, 50),
          {out, 0, ahead}, 70, 75);
  SetLobe(AddLight(scene, object, kNavigationLightGroup, {0, 5.0, 19.2}, 1, 0.95, 0.88, 30),
          {0, 0, 1}, 75, 75);
  for (double side : {-1.0, 1.0})
    SetFlash(AddLight(scene, object, kAntiCollisionLightGroup, {side * 17.2, 2.7, 0}, 0.9, 0.95, 1,
                      1500),
             1.2, 0.08, phase_s);
  for (double y : {5.3, 1.1})
    SetFlash(AddLight(scene, object, kAntiCollisionLightGroup, {0, y, -1}, 1, 0.04, 0.02, 400), 1.0,
             0.2, phase_s + 0.25);
  if (beams.landing)
    for (double side : {-1.0, 1.0})
      AddSpot(scene, object, kLandingLightGroup, {side * 4, 2.3, -3.2}, 4, 200000, 5, 11);
  if (beams.taxi) AddSpot(scene, object, kTaxiLightGroup, {0, 1.6, -15}, 6, 40000, 10, 24);
}

}  // namespace aperture
