#include "scene/builtin_scenes.h"

#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"
#include "scene/airport_scene.h"
#include "scene/benchmark_scenes.h"
#include "scene/demo_scene.h"

namespace aperture {

absl::StatusOr<BuiltinScene> FindBuiltinScene(const std::string& name) {
  if (name == "demo") return BuiltinScene{MakeDemoScene(), DemoCamera()};
  if (name == "airport") return BuiltinScene{MakeAirportScene(), DemoCamera()};
  // The benchmark scenes are laid out around a camera at the origin looking along -z.
  if (name == "triangles") return BuiltinScene{MakeTriangleFieldScene(10000), Camera{}};
  if (name == "skewed") return BuiltinScene{MakeSkewedCityScene(), Camera{}};
  if (name.rfind("tris-", 0) == 0) {
    int count = 0;
    if (!absl::SimpleAtoi(name.substr(5), &count) || count < 1 || count > kMaxTrisCount)
      return absl::InvalidArgumentError(
          absl::StrCat("built-in scene '", name, "': tris-N takes N in 1..", kMaxTrisCount));
    return BuiltinScene{MakeTrisScene(count), Camera{}};
  }
  if (name.rfind("slivers-", 0) == 0) {
    int count = 0;
    if (!absl::SimpleAtoi(name.substr(8), &count) || count < 1 || count > kMaxSliversCount)
      return absl::InvalidArgumentError(
          absl::StrCat("built-in scene '", name, "': slivers-N takes N in 1..", kMaxSliversCount));
    return BuiltinScene{MakeSliversScene(count), Camera{}};
  }
  return absl::InvalidArgumentError(absl::StrCat(
      "unknown built-in scene '", name, "' (demo, airport, triangles, skewed, tris-N, slivers-N)"));
}

}  // namespace aperture
