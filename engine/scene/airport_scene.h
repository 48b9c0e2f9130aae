// The built-in airport: the ground is a real map, Amsterdam Schiphol's aeroway features
// packed as a seed 001 vector texture (scene/airport_map.h), runways 36L and 36C painted with their
// Annex 14 markings (scene/runway_markings.h), seen 2 NM out on 36L's approach; hangars, a control
// tower with a semi-transparent (BLEND) glass cab, rows of cut-out (MASK) trees, and the demo's
// twin-jet (object "aircraft", moved by the same updates as the demo's).
#pragma once

#include "aperture/v1/scene.pb.h"
#include "scene/camera.h"

namespace aperture {

v1::Scene MakeAirportScene();

// The airport's default view: 2 NM out on 36L's 3 degree approach. At that distance the 60 m
// runway is under a degree wide, so the field of view is a telephoto 5 degrees (the frame 9 wide)
// for the runway and its markings to fill a useful part of the frame.
inline constexpr double kAirportCameraDistanceM = 3704;  // 2 NM
inline constexpr double kAirportCameraPitchDeg = -2.6;
inline constexpr double kAirportCameraFovDeg = 5;
Camera AirportCamera();

}  // namespace aperture
