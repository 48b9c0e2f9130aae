// The built-in night scene ("night"): the built-in airport (scene/airport_scene.h) after dark at
// the load 14 CFR Part 60 asks of a night visual (Appendix A, Table A1A, 6.o: detail comparable to
// 10,000 visible textured surfaces and 15,000 visible lights, 16 moving objects). The Polderbaan
// (36L, category III) and the parallel 36C (category I) lit by the Annex 14 generator
// (scene/airport_lighting.h) with their taxiways, stop bars, apron floodlights and obstacle
// lights on the tower and hangars; a town on both sides of the approach (scene/night_town.h); 16
// aircraft, named objects, each with its own navigation and anti-collision lights
// (scene/aircraft_lights.h). Seen from 2 NM out on the 3 degree approach to 36L.
#pragma once

#include <string>
#include <vector>

#include "aperture/v1/scene.pb.h"
#include "scene/camera.h"

namespace aperture {

v1::Scene MakeNightScene();

// On the 3 degree approach to 36L, 2 NM (3,704 m) from its threshold, looking at the runway
// through a 40 degree vertical field of view.
Camera NightCamera();

// The named objects that move: the demo's aircraft (kDemoAircraft) first, 16 in all.
std::vector<std::string> NightSceneAircraft();

}  // namespace aperture
