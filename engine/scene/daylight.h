// A scene's sun, ambient light, fog colour and sky from the time of day and the place: the sun's
// position (scene/sun_position.h, libnova), its colour through the air mass it crosses, the clear
// sky of Preetham, Shirley & Smits (scene/preetham_sky.h) and its light on the ground, fading
// through twilight to a moonless night. Values are in the scene's units, where a white surface
// lit by the noon sun is about 1 (docs/SCENE.md, "Time of day").
#pragma once

#include "absl/time/time.h"
#include "base/image.h"
#include "scene/sky_dome.h"
#include "scene/sun_position.h"
#include "scene/vec.h"

namespace aperture {

struct DaylightOptions {
  double turbidity = 3;  // Preetham's haze, 2..10 (2: very clear, 3: clear, 10: hazy)
  // The true bearing of the world's -z axis, degrees east of north (0: -z is north, +x east).
  double grid_north_deg = 0;
  bool operator==(const DaylightOptions&) const = default;
};

// The sun's altitude bands: day, then civil (to -6 degrees), nautical (-12) and astronomical
// (-18) twilight, then night.
enum class SkyPhase { kDay, kCivilTwilight, kNauticalTwilight, kAstronomicalTwilight, kNight };
SkyPhase PhaseOf(double sun_altitude_deg);
const char* PhaseName(SkyPhase phase);

struct Daylight {
  SunPosition sun;
  SkyPhase phase = SkyPhase::kDay;
  Vec3 sun_direction{0, 1, 0};  // world, unit, towards the sun (also below the horizon)
  Rgba sun_color{0, 0, 0, 1};   // direct light on a surface facing the sun: 0 once it has set
  Rgba ambient{0, 0, 0, 1};     // the sky's light on a horizontal surface
  Rgba fog_color{0, 0, 0, 1};   // the horizon's sky
  Rgba sky{0, 0, 0, 1};         // the zenith's sky (a one-colour stand-in)
  SkyDome dome;
  // The display's white in cd/m2: the sky and light are divided by it (a partial adaptation to
  // the light of the hour).
  double white_cd_m2 = 0;
};

// The world direction of a sun at altitude and azimuth (degrees), +y up, -z at `grid_north_deg`.
Vec3 WorldDirection(double altitude_deg, double azimuth_deg, double grid_north_deg);

// The daylight at `when` over `place` (options checked by the caller: turbidity within 2..10).
Daylight DaylightAt(absl::Time when, const GeoPlace& place, const DaylightOptions& options);

// The sun's direct light through `air_mass` relative air masses at turbidity `turbidity`, as the
// fraction of each channel that reaches the ground (alpha 1).
Rgba SunTransmittance(double air_mass, double turbidity);

// Kasten & Young (1989)'s relative optical air mass for the sun's apparent altitude (degrees):
// 1 at the zenith, about 38 at the horizon.
double RelativeAirMass(double altitude_deg);

}  // namespace aperture
