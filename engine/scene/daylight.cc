#include "scene/daylight.h"

#include <algorithm>
#include <cmath>

namespace aperture {
namespace {

// The sun's illuminance above the atmosphere at the Earth's mean distance, lux (the solar
// constant of 1361 W/m2 at the sun's 93.7 lm/W luminous efficacy).
constexpr double kSolarIlluminanceLux = 127500;
// Wavelengths (micrometres) each channel's extinction is taken at.
constexpr double kChannelMicrons[3] = {0.680, 0.550, 0.440};
// The natural moonless night sky's luminance, cd/m2 (about 22 magnitudes per square arcsecond:
// Cinzano, Falchi & Elvidge 2001's natural sky brightness, 1.7e-4 cd/m2) and its faintly blue
// colour.
constexpr double kNightSkyCdM2 = 2e-4;
// Twilight: the clear sky's luminance falls by about half a decade per degree the sun sinks
// below the horizon through civil and nautical twilight (a fit to measured zenith luminance,
// some 1.8 kcd/m2 at sunset to 3 cd/m2 at -6 degrees and 0.01 cd/m2 at -12 degrees).
constexpr double kTwilightDecadesPerDegree = 0.45;
// The display's white: 40,000 cd/m2 at 100,000 lux on the ground (a white surface in the noon
// sun about 1), following the ground's illuminance E as (E / 100,000 lux)^0.7: dusk is dimmer
// than noon and night darker still, without the ten decades between them.
constexpr double kDayWhiteCdM2 = 40000, kDayLux = 100000, kAdaptation = 0.7;
// Hemisphere sampling of the sky's light on the ground: zenith bands by azimuth sectors.
constexpr int kZenithBands = 8, kAzimuthSectors = 16;

}  // namespace

SkyPhase PhaseOf(double h) {
  if (h > -0.833) return SkyPhase::kDay;  // the sun's upper limb above the horizon
  if (h > -6) return SkyPhase::kCivilTwilight;
  if (h > -12) return SkyPhase::kNauticalTwilight;
  if (h > -18) return SkyPhase::kAstronomicalTwilight;
  return SkyPhase::kNight;
}

const char* PhaseName(SkyPhase phase) {
  switch (phase) {
    case SkyPhase::kDay:
      return "day";
    case SkyPhase::kCivilTwilight:
      return "civil twilight";
    case SkyPhase::kNauticalTwilight:
      return "nautical twilight";
    case SkyPhase::kAstronomicalTwilight:
      return "astronomical twilight";
    case SkyPhase::kNight:
      return "night";
  }
  return "day";
}

Vec3 WorldDirection(double altitude_deg, double azimuth_deg, double grid_north_deg) {
  const double h = Radians(altitude_deg), b = Radians(azimuth_deg - grid_north_deg);
  return {std::cos(h) * std::sin(b), std::sin(h), -std::cos(h) * std::cos(b)};
}

double RelativeAirMass(double altitude_deg) {
  // F. Kasten and A. T. Young, "Revised optical air mass tables and approximation formula",
  // Applied Optics 28(22), 1989: m = 1 / (sin h + 0.50572 (h + 6.07995)^-1.6364).
  const double h = std::max(altitude_deg, 0.0);
  return 1.0 / (std::sin(Radians(h)) + 0.50572 * std::pow(h + 6.07995, -1.6364));
}

Rgba SunTransmittance(double air_mass, double turbidity) {
  // Per unit air mass: Rayleigh scattering 0.008735 lambda^-4.08 (Leckner 1978) and aerosols by
  // Angstrom's law beta lambda^-1.3 with Preetham's beta = 0.04608 T - 0.04586 (appendix A.3).
  const double beta = std::max(0.0, 0.04608 * turbidity - 0.04586);
  float t[3];
  for (int c = 0; c < 3; ++c) {
    const double lambda = kChannelMicrons[c];
    const double depth = 0.008735 * std::pow(lambda, -4.08) + beta * std::pow(lambda, -1.3);
    t[c] = static_cast<float>(std::exp(-air_mass * depth));
  }
  return {t[0], t[1], t[2], 1};
}

Daylight DaylightAt(absl::Time when, const GeoPlace& place, const DaylightOptions& options) {
  Daylight d;
  d.sun = SunPositionAt(when, place);
  const double h = d.sun.altitude_deg;
  d.phase = PhaseOf(h);
  d.sun_direction = WorldDirection(h, d.sun.azimuth_deg, options.grid_north_deg);

  // The direct beam, lux per channel, on a surface facing the sun (none once the sun has set).
  Rgba beam{0, 0, 0, 1};
  if (h > 0) {
    const Rgba t = SunTransmittance(RelativeAirMass(h), options.turbidity);
    const auto e = static_cast<float>(kSolarIlluminanceLux);
    beam = {e * t.r, e * t.g, e * t.b, 1};
  }

  // The sky: Preetham's with the sun held on the horizon once it has set, fading and turning
  // blue through twilight (the ozone's Chappuis band absorbs the long light path's red).
  d.dome.analytic = true;
  d.dome.model =
      PreethamSky(WorldDirection(std::max(h, 0.0), d.sun.azimuth_deg, options.grid_north_deg),
                  options.turbidity);
  const double depression = std::clamp(-h, 0.0, 18.0);
  const double fade = std::pow(10.0, -kTwilightDecadesPerDegree * depression);
  const double blue = std::min(depression / 6.0, 1.0);
  const double tint[3] = {1 - 0.6 * blue, 1 - 0.3 * blue, 1};

  // The ground's light from the sky (E = integral of L cos theta d omega, midpoint rule), in lux
  // per channel, before the display's white is known.
  double sky_lux[3] = {0, 0, 0};
  for (int i = 0; i < kZenithBands; ++i) {
    const double theta = (i + 0.5) * (kPi / 2) / kZenithBands;
    const double d_omega = std::sin(theta) * (kPi / 2 / kZenithBands) * (2 * kPi / kAzimuthSectors);
    for (int j = 0; j < kAzimuthSectors; ++j) {
      const double phi = (j + 0.5) * 2 * kPi / kAzimuthSectors;
      const Vec3 dir{std::sin(theta) * std::cos(phi), std::cos(theta),
                     std::sin(theta) * std::sin(phi)};
      const Rgba l = d.dome.model.Radiance(dir);  // kcd/m2
      const double w = 1000 * fade * std::cos(theta) * d_omega;
      sky_lux[0] += l.r * w * tint[0], sky_lux[1] += l.g * w * tint[1];
      sky_lux[2] += l.b * w * tint[2];
    }
  }
  const double night_lux = kPi * kNightSkyCdM2;
  const double ground_lux = std::max(0.0, std::sin(Radians(h))) * beam.g + sky_lux[1] + night_lux;
  d.white_cd_m2 = kDayWhiteCdM2 * std::pow(ground_lux / kDayLux, kAdaptation);

  const double unit = 1.0 / d.white_cd_m2;  // scene units per cd/m2
  // A Lambertian surface of albedo 1 under illuminance E shows luminance E / pi.
  const auto lit = [&](double lux) { return static_cast<float>(lux * unit / kPi); };
  d.sun_color = {lit(beam.r), lit(beam.g), lit(beam.b), 1};
  d.ambient = {lit(sky_lux[0] + night_lux), lit(sky_lux[1] + night_lux),
               lit(sky_lux[2] + night_lux), 1};
  const double per_kcd = 1000 * fade * unit;
  d.dome.scale = {static_cast<float>(per_kcd * tint[0]), static_cast<float>(per_kcd * tint[1]),
                  static_cast<float>(per_kcd * tint[2]), 1};
  const auto night = static_cast<float>(kNightSkyCdM2 * unit);
  d.dome.floor = {0.8f * night, 0.9f * night, night, 1};

  d.sky = d.dome.Radiance({0, 1, 0});
  Rgba horizon{0, 0, 0, 1};
  for (int j = 0; j < kAzimuthSectors; ++j) {
    const double phi = (j + 0.5) * 2 * kPi / kAzimuthSectors;
    const Rgba l = d.dome.Radiance({std::cos(phi), 0, std::sin(phi)});
    horizon = horizon + l * (1.0f / kAzimuthSectors);
  }
  horizon.a = 1;
  d.fog_color = horizon;
  return d;
}

}  // namespace aperture
