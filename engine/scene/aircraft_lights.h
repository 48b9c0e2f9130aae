// An aircraft's own lights, attached to its named object (LightPoint.object) so that they move,
// turn and hide with it: navigation lights (red on the left wing tip, green on the right, white
// on the tail), white anti-collision strobes on the wing tips, a flashing red beacon on top and,
// on the runway and in the air, two landing lights; taxiing, a taxi light on the nose gear. The
// landing and taxi lights are spot lights (scene/spot_lights.h): they light the runway or taxiway
// ahead, and their lamps are light points. Placed for the demo's twin-jet (scene/demo_geometry.h:
// nose towards -z, wings to x = +-17 m at y = 2.4-2.8 m, tail at z = 19 m).
#pragma once

#include <string>

#include "aperture/v1/scene.pb.h"

namespace aperture {

inline constexpr char kNavigationLightGroup[] = "aircraft-navigation";
inline constexpr char kAntiCollisionLightGroup[] = "aircraft-anticollision";
inline constexpr char kLandingLightGroup[] = "aircraft-landing";
inline constexpr char kTaxiLightGroup[] = "aircraft-taxi";

// Which of its beams an aircraft has on.
struct AircraftBeams {
  bool landing = false;  // two landing lights (spot lights)
  bool taxi = false;     // a taxi light (a spot light)
};

// Appends the lights of the aircraft that object `object` places. Its strobes and beacon flash
// `phase_s` later than scene time 0 (aircraft flash out of step with each other).
void AddAircraftLights(const std::string& object, double phase_s, AircraftBeams beams,
                       v1::Scene* scene);

}  // namespace aperture
