// The built-in airport (issue 24): the ground is a real map, Amsterdam Schiphol's aeroway features
// packed as a seed 001 vector texture (scene/airport_map.h), runway 18R/36L lined up with the
// demo's camera on final approach; hangars, a control tower with a semi-transparent (BLEND)
// glass cab, rows of cut-out (MASK) trees, and the demo's twin-jet (object "aircraft", moved by
// the same updates as the demo's).
#pragma once

#include "aperture/v1/scene.pb.h"

namespace aperture {

v1::Scene MakeAirportScene();

}  // namespace aperture
