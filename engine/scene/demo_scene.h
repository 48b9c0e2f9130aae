// The built-in demo: an airfield seen from a camera on final approach (a low grazing angle,
// where texture filtering matters most). A proto Scene, self-contained (its textures are
// generated and embedded as PNG bytes), so the client can send it to a server as it is.
#pragma once

#include "aperture/v1/scene.pb.h"
#include "scene/camera.h"

namespace aperture {

v1::Scene MakeDemoScene();

// The demo's moving object: a twin-jet lined up on the runway (object name "aircraft").
inline constexpr char kDemoAircraft[] = "aircraft";
// Its transform `seconds` into its take-off roll (0: where the scene puts it).
v1::Transform DemoAircraftAt(double seconds);
// On final approach: 14 m up, 220 m before the threshold, looking 5 degrees down.
Camera DemoCamera();

}  // namespace aperture
