#include "raster/aa_filter.h"

namespace aperture {

const char* AntiAliasingName(AntiAliasing aa) {
  switch (aa) {
    case AntiAliasing::kBox1:
      return "box1";
    case AntiAliasing::kBox2:
      return "box2";
    case AntiAliasing::kTent2:
      return "tent2";
  }
  return "?";
}

}  // namespace aperture
