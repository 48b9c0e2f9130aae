// The scenes built into every tool and the server, by name: "demo" (the airfield on final
// approach), "airport" (the same approach to a real airport's map, scene/airport_scene.h),
// "night" (that airport after dark, lit to ICAO Annex 14, with a town and 16 aircraft,
// scene/night_scene.h), "triangles" (10,000 random triangles), "skewed" (a dense city block in
// one corner of the view), "tris-N" (the peer benchmark's scene of N triangles painted in
// order) and "slivers-N" (N slivers on 13 planes, the service tests' slow frame). Each comes with
// the camera it is meant to be seen from.
#pragma once

#include <string>

#include "absl/status/statusor.h"
#include "aperture/v1/scene.pb.h"
#include "scene/camera.h"

namespace aperture {

struct BuiltinScene {
  v1::Scene scene;
  Camera camera;
};

// The largest N of "tris-N" (the peer benchmark's largest scene).
inline constexpr int kMaxTrisCount = 1000000;
// The largest N of "slivers-N".
inline constexpr int kMaxSliversCount = 1000000;

// Whether `name` starts like a built-in family named with a count ("tris-", "slivers-"): such a
// name is never a file, so its error (a count out of range) is the one to report.
bool NamesCountedBuiltinScene(const std::string& name);

// InvalidArgument naming the known scenes for any other name.
absl::StatusOr<BuiltinScene> FindBuiltinScene(const std::string& name);

}  // namespace aperture
