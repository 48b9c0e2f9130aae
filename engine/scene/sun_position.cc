#include "scene/sun_position.h"

#include <libnova/refraction.h>
#include <libnova/transform.h>

#include <cmath>

#include "absl/strings/str_cat.h"

namespace aperture {
namespace {

// The Julian day of the Unix epoch, 1970-01-01T00:00Z.
constexpr double kUnixEpochJulianDay = 2440587.5;

double Sin(double deg) { return std::sin(deg * (M_PI / 180)); }
double Cos(double deg) { return std::cos(deg * (M_PI / 180)); }

}  // namespace

SunEquatorial ApparentSunEquatorial(double jd) {
  // J. Meeus, "Astronomical Algorithms" (2nd ed.), chapter 25, eqs. 25.2-25.8 and 22.2 (0.01
  // degree). libnova's own ln_get_solar_equ_coords (Debian's 0.16) is not used: its VSOP87 Earth
  // longitude is 0.10 degree off Meeus's example 25.b in 1992 and 0.37 degree off NOAA's figures
  // in 2026, which moves the noon sun 0.75 degree in azimuth at Schiphol.
  const double t = (jd - 2451545.0) / 36525;
  const double l0 = 280.46646 + t * (36000.76983 + t * 0.0003032);  // mean longitude
  const double m = 357.52911 + t * (35999.05029 - t * 0.0001537);   // mean anomaly
  const double c = Sin(m) * (1.914602 - t * (0.004817 + t * 0.000014)) +
                   Sin(2 * m) * (0.019993 - t * 0.000101) + Sin(3 * m) * 0.000289;
  const double omega = 125.04 - 1934.136 * t;
  const double lambda = l0 + c - 0.00569 - 0.00478 * Sin(omega);  // apparent longitude
  const double epsilon0 =
      23 + (26 + (21.448 - t * (46.8150 + t * (0.00059 - t * 0.001813))) / 60) / 60;
  const double epsilon = epsilon0 + 0.00256 * Cos(omega);  // apparent obliquity
  SunEquatorial sun;
  sun.right_ascension_deg = std::atan2(Cos(epsilon) * Sin(lambda), Cos(lambda)) * (180 / M_PI);
  if (sun.right_ascension_deg < 0) sun.right_ascension_deg += 360;
  sun.declination_deg = std::asin(Sin(epsilon) * Sin(lambda)) * (180 / M_PI);
  return sun;
}

absl::StatusOr<absl::Time> ParseUtc(const std::string& text, const std::string& where) {
  // With seconds (fractions allowed) or without, the offset "Z" or +hh:mm.
  for (const char* format : {"%Y-%m-%dT%H:%M:%E*S%Ez", "%Y-%m-%dT%H:%M%Ez"}) {
    absl::Time t;
    std::string error;
    if (absl::ParseTime(format, text, absl::UTCTimeZone(), &t, &error)) return t;
  }
  return absl::InvalidArgumentError(
      absl::StrCat(where, ": '", text.substr(0, 64),
                   "' is not an ISO 8601 date and time with its offset (e.g. 2026-06-21T12:00Z)"));
}

absl::Status ValidatePlace(const GeoPlace& place, const std::string& where) {
  if (!(place.latitude_deg >= -90 && place.latitude_deg <= 90))
    return absl::InvalidArgumentError(
        absl::StrCat(where, ".latitude_deg: must be within [-90, 90], is ", place.latitude_deg));
  if (!(place.longitude_deg >= -180 && place.longitude_deg <= 180))
    return absl::InvalidArgumentError(absl::StrCat(
        where, ".longitude_deg: must be within [-180, 180], is ", place.longitude_deg));
  return absl::OkStatus();
}

SunPosition SunPositionAt(absl::Time when, const GeoPlace& place) {
  const double jd = absl::ToDoubleSeconds(when - absl::UnixEpoch()) / 86400.0 + kUnixEpochJulianDay;
  const SunEquatorial sun_place = ApparentSunEquatorial(jd);
  ln_equ_posn equatorial{sun_place.right_ascension_deg, sun_place.declination_deg};
  ln_lnlat_posn observer{place.longitude_deg, place.latitude_deg};
  ln_hrz_posn horizontal{};
  ln_get_hrz_from_equ(&equatorial, &observer, jd, &horizontal);
  // libnova measures azimuth from the south towards the west.
  SunPosition sun;
  sun.azimuth_deg = std::fmod(horizontal.az + 180.0, 360.0);
  // Refraction lifts the sun near the horizon (standard atmosphere, 1010 hPa, 10 C: Meeus eq.
  // 16.4); below -2 degrees it no longer matters for the light.
  sun.altitude_deg = horizontal.alt;
  if (horizontal.alt > -2.0) sun.altitude_deg += ln_get_refraction_adj(horizontal.alt, 1010, 10);
  return sun;
}

}  // namespace aperture
