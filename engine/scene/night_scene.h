// The built-in night scene ("night"): the built-in airport (scene/airport_scene.h) after dark, at
// the load 14 CFR Part 60 asks of a night visual (Appendix A, Table A1A, 6.o: 10,000 visible
// textured surfaces, 15,000 visible lights, 16 moving objects). The Polderbaan (36L, category III)
// and the parallel 36C (category I) lit by the Annex 14 generator (scene/airport_lighting.h) at a
// night brightness step, with their taxiways, stop bars, apron floodlights and obstacle lights on
// the tower and hangars; a town west of the runway and on both sides of the approach, crossed by
// a lit motorway (scene/night_town.h); 16 aircraft, named objects, each with its own navigation
// and anti-collision lights, those on the runways with landing lights and those taxiing with a
// taxi light, spot lights that light the ground ahead (scene/aircraft_lights.h). Seen from 1 NM out
// on the 3 degree approach to 36L. docs/SCENE.md, "The night scene", counts its lights by kind.
#pragma once

#include <string>
#include <vector>

#include "aperture/v1/scene.pb.h"
#include "scene/camera.h"

namespace aperture {

v1::Scene MakeNightScene();
// The same airport, town and aircraft by day ("night-by-day"): the built-in airport's sun, sky
// and haze, and no light points. What a night frame's cost is compared with.
v1::Scene MakeNightSceneByDay();

// On the 3 degree approach to 36L, 1 NM (1,852 m) from its threshold, looking 4 degrees down
// the approach through a 30 degree vertical field of view (the approach lights, the runway and the
// town either side in one frame).
Camera NightCamera();

// The named objects that move: the demo's aircraft (kDemoAircraft) first, 16 in all.
std::vector<std::string> NightSceneAircraft();

}  // namespace aperture
