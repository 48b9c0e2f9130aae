// The built-in airport's two runways as the lighting and the markings take them: the Polderbaan
// landing 36L where the airport places it (3,800 m x 60 m from its threshold at (0, 0, 200) along
// -z, category III) and the parallel 36C where the map shows it (45 m wide, category I).
#pragma once

#include "scene/airport_lighting.h"

namespace aperture {

RunwayDescription Polderbaan36L();
RunwayDescription Zwanenburgbaan36C();

}  // namespace aperture
