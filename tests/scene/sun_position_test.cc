// The sun's position from libnova against published figures, and ISO 8601 times and places
// refused with the field named.
#include "scene/sun_position.h"

#include <gtest/gtest.h>

#include <cmath>

namespace aperture {
namespace {

absl::Time Utc(const std::string& text) {
  auto t = ParseUtc(text, "utc");
  EXPECT_TRUE(t.ok()) << t.status();
  return t.ok() ? *t : absl::UnixEpoch();
}

// The difference of two azimuths, degrees, in [-180, 180).
double AzimuthDifference(double a, double b) { return std::remainder(a - b, 360.0); }

struct NoaaFigure {
  const char* utc;
  double latitude, longitude;
  double altitude, azimuth;  // apparent (refraction included), degrees; azimuth from north
};

// NOAA's solar calculator (Global Monitoring Laboratory, gml.noaa.gov/grad/solcalc), as its
// published spreadsheet NOAA_Solar_Calculations_day.xls computes it (Meeus's solar coordinates,
// NOAA's refraction): "Solar Elevation corrected for atm refraction" and "Solar Azimuth (deg cw
// from N)" for these dates, times (UTC) and places, the spreadsheet's formulae evaluated for each.
constexpr NoaaFigure kNoaa[] = {
    {"2026-06-21T12:00Z", 52.31, 4.76, 60.9499, 188.1498},      // Schiphol, midsummer
    {"2026-06-21T06:00Z", 52.31, 4.76, 20.9572, 78.3563},       // Schiphol, morning
    {"2026-12-21T12:00Z", 52.31, 4.76, 14.1771, 184.9573},      // Schiphol, midwinter
    {"2026-03-20T15:30Z", 52.31, 4.76, 20.3631, 241.3893},      // Schiphol, equinox afternoon
    {"2026-09-01T09:00Z", -33.87, 151.21, -17.9695, 267.8757},  // Sydney, night
};

TEST(SunPosition, MatchesNoaaSolarCalculator) {
  for (const NoaaFigure& f : kNoaa) {
    const SunPosition sun = SunPositionAt(Utc(f.utc), {f.latitude, f.longitude});
    EXPECT_NEAR(sun.altitude_deg, f.altitude, 0.1) << f.utc << " at " << f.latitude;
    EXPECT_NEAR(AzimuthDifference(sun.azimuth_deg, f.azimuth), 0, 0.1)
        << f.utc << " at " << f.latitude;
  }
}

// J. Meeus, "Astronomical Algorithms" (2nd ed., 1998), example 25.a: the sun's apparent place on
// 1992 October 13.0 TD (JDE 2448908.5): right ascension 198.38083 degrees, declination
// -7.78507 degrees (and by the full VSOP87 theory, example 25.b, 198.378121 and -7.783817).
TEST(SunPosition, ApparentPlaceMatchesMeeusExample) {
  const SunEquatorial sun = ApparentSunEquatorial(2448908.5);
  EXPECT_NEAR(sun.right_ascension_deg, 198.38083, 0.001);
  EXPECT_NEAR(sun.declination_deg, -7.78507, 0.001);
  EXPECT_NEAR(sun.right_ascension_deg, 198.378121, 0.01);
  EXPECT_NEAR(sun.declination_deg, -7.783817, 0.01);
}

TEST(SunPosition, MiddayAtSchipholIsSouthAndHighestInJune) {
  // Local apparent noon at 4.76 E is near 11:40 UTC: the sun is close to due south, at its
  // highest, 90 - 52.31 + 23.44 degrees.
  const SunPosition sun = SunPositionAt(Utc("2026-06-21T11:40Z"), {52.31, 4.76});
  EXPECT_NEAR(AzimuthDifference(sun.azimuth_deg, 180), 0, 2.0);
  EXPECT_NEAR(sun.altitude_deg, 90 - 52.31 + 23.44, 0.1);
}

TEST(SunPosition, ParsesIso8601WithOffsets) {
  EXPECT_EQ(Utc("2026-06-21T12:00Z"), Utc("2026-06-21T12:00:00Z"));
  EXPECT_EQ(Utc("2026-06-21T14:00+02:00"), Utc("2026-06-21T12:00Z"));
  EXPECT_EQ(Utc("2026-06-21T12:00:30.5Z") - Utc("2026-06-21T12:00Z"), absl::Milliseconds(30500));
}

TEST(SunPosition, RefusesUnparseableTimesNamingTheField) {
  for (const char* bad : {"", "noon", "2026-06-21", "2026-13-01T00:00Z", "2026-06-21T12:00"}) {
    auto t = ParseUtc(bad, "time_of_day.utc");
    ASSERT_FALSE(t.ok()) << bad;
    EXPECT_EQ(t.status().code(), absl::StatusCode::kInvalidArgument);
    EXPECT_NE(t.status().message().find("time_of_day.utc"), std::string::npos) << t.status();
  }
}

TEST(SunPosition, RefusesPlacesOutOfRangeNamingTheField) {
  auto s = ValidatePlace({95, 4.76}, "time_of_day.place");
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.message().find("time_of_day.place.latitude_deg"), std::string::npos) << s;
  s = ValidatePlace({52.31, 181}, "time_of_day.place");
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.message().find("time_of_day.place.longitude_deg"), std::string::npos) << s;
  s = ValidatePlace({NAN, 0}, "time_of_day.place");
  EXPECT_FALSE(s.ok());
  EXPECT_TRUE(ValidatePlace({-90, 180}, "time_of_day.place").ok());
}

}  // namespace
}  // namespace aperture
