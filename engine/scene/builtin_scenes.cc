#include "scene/builtin_scenes.h"

#include "absl/strings/str_cat.h"
#include "scene/benchmark_scenes.h"
#include "scene/demo_scene.h"

namespace aperture {

absl::StatusOr<BuiltinScene> FindBuiltinScene(const std::string& name) {
  if (name == "demo") return BuiltinScene{MakeDemoScene(), DemoCamera()};
  // The benchmark scenes are laid out around a camera at the origin looking along -z.
  if (name == "triangles") return BuiltinScene{MakeTriangleFieldScene(10000), Camera{}};
  if (name == "skewed") return BuiltinScene{MakeSkewedCityScene(), Camera{}};
  return absl::InvalidArgumentError(
      absl::StrCat("unknown built-in scene '", name, "' (demo, triangles, skewed)"));
}

}  // namespace aperture
