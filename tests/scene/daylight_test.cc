// The daylight model: Preetham, Shirley & Smits's sky against the paper's formula, brighter
// towards the horizon and the sun; the sun reddened by the air mass; twilight and night.
#include "scene/daylight.h"

#include <gtest/gtest.h>

#include <cmath>

#include "scene/preetham_sky.h"

namespace aperture {
namespace {

Vec3 Direction(double altitude_deg, double azimuth_deg) {
  return WorldDirection(altitude_deg, azimuth_deg, 0);
}

// Preetham et al. 1999, eq. 3 and appendix A.2, written out here for turbidity 3 (the
// coefficients' values at T = 3): the luminance's Perez function and the zenith luminance.
double PaperLuminance(double theta, double gamma, double theta_s) {
  const double a = 0.1787 * 3 - 1.4630, b = -0.3554 * 3 + 0.4275, c = -0.0227 * 3 + 5.3251,
               d = 0.1206 * 3 - 2.5771, e = -0.0670 * 3 + 0.3703;
  const auto f = [&](double th, double g) {
    return (1 + a * std::exp(b / std::cos(th))) *
           (1 + c * std::exp(d * g) + e * std::cos(g) * std::cos(g));
  };
  const double chi = (4.0 / 9 - 3.0 / 120) * (kPi - 2 * theta_s);
  const double zenith = (4.0453 * 3 - 4.9710) * std::tan(chi) - 0.2155 * 3 + 2.4192;
  return zenith * f(theta, gamma) / f(0, theta_s);
}

TEST(PreethamSky, LuminanceFollowsThePapersFormula) {
  const double sun_altitude = 35, sun_azimuth = 200;
  const PreethamSky sky(Direction(sun_altitude, sun_azimuth), 3);
  const double theta_s = Radians(90 - sun_altitude);
  for (const auto& [alt, az] : {std::pair{90.0, 0.0},
                                {60.0, 200.0},
                                {20.0, 20.0},
                                {5.0, 110.0},
                                {10.0, 210.0},
                                {45.0, 300.0}}) {
    const Vec3 dir = Direction(alt, az);
    const double gamma = std::acos(Dot(dir, sky.sun()));
    double Y = 0, x = 0, y = 0;
    sky.LuminanceXy(dir, &Y, &x, &y);
    EXPECT_NEAR(Y, PaperLuminance(Radians(90 - alt), gamma, theta_s), 1e-9)
        << "altitude " << alt << " azimuth " << az;
    EXPECT_GT(x, 0.2);  // a plausible daylight chromaticity
    EXPECT_LT(x, 0.45);
  }
  // The paper's figure for the zenith at T = 3, sun 55 degrees from the zenith: about 5.5 kcd/m2.
  EXPECT_NEAR(sky.zenith_luminance(), PaperLuminance(0, theta_s, theta_s), 1e-9);
  EXPECT_GT(sky.zenith_luminance(), 4);
  EXPECT_LT(sky.zenith_luminance(), 7);
}

TEST(PreethamSky, BrighterTowardsTheHorizonAndTheSun) {
  const PreethamSky sky(Direction(30, 180), 3);
  double y_high = 0, y_low = 0, y_sun = 0, y_far = 0, unused = 0;
  // Opposite the sun: the horizon is brighter than high up.
  sky.LuminanceXy(Direction(50, 0), &y_high, &unused, &unused);
  sky.LuminanceXy(Direction(3, 0), &y_low, &unused, &unused);
  EXPECT_GT(y_low, 1.5 * y_high);
  // At the sun's altitude, towards the sun is brighter than 90 degrees away.
  sky.LuminanceXy(Direction(30, 175), &y_sun, &unused, &unused);
  sky.LuminanceXy(Direction(30, 90), &y_far, &unused, &unused);
  EXPECT_GT(y_sun, 3 * y_far);
  // Below the horizon the horizon's value.
  double y_below = 0, y_on = 0;
  sky.LuminanceXy(Direction(-10, 40), &y_below, &unused, &unused);
  sky.LuminanceXy(Direction(0, 40), &y_on, &unused, &unused);
  EXPECT_DOUBLE_EQ(y_below, y_on);
}

TEST(Daylight, AirMassFollowsKastenAndYoung) {
  EXPECT_NEAR(RelativeAirMass(90), 1.0, 1e-3);
  EXPECT_NEAR(RelativeAirMass(30), 1.995, 0.01);  // about 1 / sin 30
  // At the horizon the formula gives 37.92 (Kasten & Young's table: 38.09, within 0.5 %).
  EXPECT_NEAR(RelativeAirMass(0), 37.92, 0.01);
}

TEST(Daylight, TheSunReddensTowardsTheHorizon) {
  const Rgba high = SunTransmittance(RelativeAirMass(60), 3);
  const Rgba low = SunTransmittance(RelativeAirMass(3), 3);
  EXPECT_GT(high.g, 0.6);
  EXPECT_GT(high.r, high.g);
  EXPECT_GT(high.g, high.b);
  // Blue is lost first: the low sun's blue over red is far below the high sun's.
  EXPECT_LT(low.b / low.r, 0.25 * (high.b / high.r));
  EXPECT_LT(low.g, high.g);
}

absl::Time At(const char* text) { return *ParseUtc(text, "utc"); }

TEST(Daylight, DayDuskAndNightAtSchiphol) {
  const GeoPlace schiphol{52.31, 4.76};
  const Daylight noon = DaylightAt(At("2026-06-21T12:00Z"), schiphol, {});
  EXPECT_EQ(noon.phase, SkyPhase::kDay);
  EXPECT_NEAR(std::asin(noon.sun_direction.y) * 180 / kPi, noon.sun.altitude_deg, 1e-9);
  // A white surface facing the noon sun is about 1 (ambient and sun).
  EXPECT_GT(noon.sun_color.g + noon.ambient.g, 0.6);
  EXPECT_LT(noon.sun_color.g + noon.ambient.g, 2.0);
  EXPECT_GT(noon.ambient.b, noon.ambient.r);  // the blue sky's light

  // Sunset on 21 June 2026 at Schiphol is near 20:07 UTC: 20 minutes later, civil twilight.
  const Daylight dusk = DaylightAt(At("2026-06-21T20:27Z"), schiphol, {});
  EXPECT_EQ(dusk.phase, SkyPhase::kCivilTwilight);
  EXPECT_EQ(dusk.sun_color.g, 0);
  // In lux the sky's light falls by more than two decades; on the display, which adapts in part,
  // dusk is still dimmer than noon.
  EXPECT_LT(dusk.ambient.g * dusk.white_cd_m2, 0.01 * noon.ambient.g * noon.white_cd_m2);
  EXPECT_LT(dusk.ambient.g + dusk.sun_color.g, 0.5 * (noon.ambient.g + noon.sun_color.g));
  EXPECT_GT(dusk.ambient.g, 0);
  // Towards the sunset the horizon glows brighter than opposite it.
  const Rgba west = dusk.dome.Radiance(Direction(2, dusk.sun.azimuth_deg));
  const Rgba east = dusk.dome.Radiance(Direction(2, dusk.sun.azimuth_deg + 180));
  EXPECT_GT(west.g, east.g);

  // Midwinter midnight: moonless night, small ambient, a dark sky.
  const Daylight night = DaylightAt(At("2026-12-21T00:00Z"), schiphol, {});
  EXPECT_EQ(night.phase, SkyPhase::kNight);
  EXPECT_LT(night.ambient.g, 0.02);
  EXPECT_GT(night.ambient.g, 0);
  EXPECT_LT(night.dome.Radiance({0, 1, 0}).g, 0.02);
}

TEST(Daylight, PhasesFollowTheSunsDepression) {
  EXPECT_EQ(PhaseOf(10), SkyPhase::kDay);
  EXPECT_EQ(PhaseOf(-3), SkyPhase::kCivilTwilight);
  EXPECT_EQ(PhaseOf(-9), SkyPhase::kNauticalTwilight);
  EXPECT_EQ(PhaseOf(-15), SkyPhase::kAstronomicalTwilight);
  EXPECT_EQ(PhaseOf(-25), SkyPhase::kNight);
}

TEST(Daylight, GridNorthTurnsTheSun) {
  // The sun due east (azimuth 90) is +x with -z north, and -z when -z points 90 degrees east.
  const Vec3 east = WorldDirection(0, 90, 0);
  EXPECT_NEAR(east.x, 1, 1e-12);
  const Vec3 turned = WorldDirection(0, 90, 90);
  EXPECT_NEAR(turned.z, -1, 1e-12);
}

}  // namespace
}  // namespace aperture
