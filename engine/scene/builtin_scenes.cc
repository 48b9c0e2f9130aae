#include "scene/builtin_scenes.h"

#include "absl/strings/match.h"
#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"
#include "scene/airport_scene.h"
#include "scene/benchmark_scenes.h"
#include "scene/demo_scene.h"
#include "scene/night_scene.h"

namespace aperture {
namespace {

// The benchmark families named with a count, "tris-N" and "slivers-N".
struct Family {
  absl::string_view prefix;
  int max_count;
  v1::Scene (*make)(int count);
};
constexpr Family kFamilies[] = {
    {"tris-", kMaxTrisCount, [](int count) { return MakeTrisScene(count); }},
    {"slivers-", kMaxSliversCount, [](int count) { return MakeSliversScene(count); }},
};

}  // namespace

bool NamesCountedBuiltinScene(const std::string& name) {
  for (const Family& family : kFamilies)
    if (absl::StartsWith(name, family.prefix)) return true;
  return false;
}

absl::StatusOr<BuiltinScene> FindBuiltinScene(const std::string& name) {
  if (name == "demo") return BuiltinScene{MakeDemoScene(), DemoCamera()};
  if (name == "airport") return BuiltinScene{MakeAirportScene(), AirportCamera()};
  if (name == "night") return BuiltinScene{MakeNightScene(), NightCamera()};
  if (name == "night-by-day") return BuiltinScene{MakeNightSceneByDay(), NightCamera()};
  // The benchmark scenes are laid out around a camera at the origin looking along -z.
  if (name == "triangles") return BuiltinScene{MakeTriangleFieldScene(10000), Camera{}};
  if (name == "skewed") return BuiltinScene{MakeSkewedCityScene(), Camera{}};
  for (const Family& family : kFamilies) {
    if (!absl::StartsWith(name, family.prefix)) continue;
    int count = 0;
    if (!absl::SimpleAtoi(absl::string_view(name).substr(family.prefix.size()), &count) ||
        count < 1 || count > family.max_count)
      return absl::InvalidArgumentError(absl::StrCat("built-in scene '", name, "': ", family.prefix,
                                                     "N takes N in 1..", family.max_count));
    return BuiltinScene{family.make(count), Camera{}};
  }
  return absl::InvalidArgumentError(
      absl::StrCat("unknown built-in scene '", name,
                   "' (demo, airport, night, night-by-day, triangles, skewed, tris-N, slivers-N)"));
}

}  // namespace aperture
