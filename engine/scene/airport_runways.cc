#include "scene/airport_runways.h"

#include <cmath>

#include "scene/airport_map.h"

namespace aperture {

RunwayDescription Polderbaan36L() {
  RunwayDescription r;
  r.designator = "36L";
  r.threshold = {0, 0, 200};
  r.heading_deg = 0;
  r.length_m = 3800;
  r.width_m = 60;
  r.category = RunwayCategory::kPrecisionCatIII;
  return r;
}

RunwayDescription Zwanenburgbaan36C() {
  RunwayDescription r;
  r.designator = "36C";
  r.threshold = AirportMapToWorld(k36CSouthX, k36CSouthY);
  const Vec3 d = AirportMapToWorld(k36CNorthX, k36CNorthY) - r.threshold;
  r.heading_deg = std::atan2(-d.x, -d.z) * 180 / kPi;
  r.length_m = Length(d);
  r.width_m = 45;
  r.category = RunwayCategory::kPrecisionCatI;
  return r;
}

}  // namespace aperture
