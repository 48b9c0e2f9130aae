// Where the sun stands for an observer on the ground at an instant (UTC): the sun's apparent
// equatorial place by Meeus ("Astronomical Algorithms", chapter 25), then Debian's libnova for
// the sidereal time, the horizontal coordinates and the atmosphere's refraction near the horizon,
// as a navigator or NOAA's solar calculator reports the sun.
#pragma once

#include <string>

#include "absl/status/statusor.h"
#include "absl/time/time.h"

namespace aperture {

// A place on the Earth: latitude north positive, longitude east positive, degrees.
struct GeoPlace {
  double latitude_deg = 0, longitude_deg = 0;
  bool operator==(const GeoPlace&) const = default;
};

// The sun seen from a place: apparent altitude above the horizon (refraction included) and azimuth
// from true north towards the east, degrees.
struct SunPosition {
  double altitude_deg = 0, azimuth_deg = 0;
};

// An ISO 8601 date and time with its UTC offset ("2026-06-21T12:00Z", "2026-06-21T12:00:30Z",
// "2026-06-21T14:00+02:00", fractional seconds allowed); an error naming `where` otherwise.
absl::StatusOr<absl::Time> ParseUtc(const std::string& text, const std::string& where);

// Checks a place's ranges (latitude within [-90, 90], longitude within [-180, 180]); the error
// names `where`.latitude_deg or .longitude_deg.
absl::Status ValidatePlace(const GeoPlace& place, const std::string& where);

// The sun's apparent right ascension and declination (degrees) at Julian day `jd` (UT), 0.01
// degree (Meeus's chapter 25).
struct SunEquatorial {
  double right_ascension_deg = 0, declination_deg = 0;
};
SunEquatorial ApparentSunEquatorial(double jd);

// The sun's position at `when` seen from `place` (a standard atmosphere's refraction).
SunPosition SunPositionAt(absl::Time when, const GeoPlace& place);

}  // namespace aperture
