// An aircraft's own lights, attached to its named object (LightPoint.object) so that they move,
// turn and hide with it: navigation lights (red on the left wing tip, green on the right, white
// on the tail), white anti-collision strobes on the wing tips, a flashing red beacon on top and,
// on approach, landing lights. Placed for the demo's twin-jet (scene/demo_geometry.h: nose
// towards -z, wings to x = +-17 m at y = 2.4-2.8 m, tail at z = 19 m).
#pragma once

#include <string>

#include "aperture/v1/scene.pb.h"

namespace aperture {

inline constexpr char kNavigationLightGroup[] = "aircraft-navigation";
inline constexpr char kAntiCollisionLightGroup[] = "aircraft-anticollision";
inline constexpr char kLandingLightGroup[] = "aircraft-landing";

// Appends the lights of the aircraft that object `object` places. Its strobes and beacon flash
// `phase_s` later than scene time 0 (aircraft flash out of step with each other).
void AddAircraftLights(const std::string& object, double phase_s, bool landing_lights,
                       v1::Scene* scene);

}  // namespace aperture
