// What `aperture sim` sends in each slot: a camera, the scene's clock and, when something
// changes, a scene update. The clock (RenderFrameRequest.scene_time_s, which flashing lights are
// on) runs with the slots: frame i is at i / rate seconds, unless a JSON line sets its own.
// From a path file (docs/SERVICE.md, "Path files"):
//   - CSV lines X,Y,Z,YAW,PITCH,ROLL: a camera per frame;
//   - JSON lines: one aperture.v1.RenderFrameRequest in proto3 JSON per line, of which `camera`,
//     `update` and `scene_time_s` are used ({"camera": {...}, "update": {"objects": [...], "fog":
//     {...}}}); a line without a camera keeps the previous one, a camera without fov, near or far
//     takes the command line's;
//   - '#' lines and blank lines are skipped; both kinds may mix.
// Without a file: the default flight, the camera forward at 60 m/s along -z and every named
// object of the scene (the demo's aircraft) rolling forward along its heading at 2 m/s^2.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "aperture/v1/render_service.pb.h"

namespace aperture {

struct SimFrame {
  v1::Camera camera;
  std::optional<v1::SceneUpdate> update;
  double scene_time_s = 0;
};

// At most `frames` frames (fewer when the file has fewer lines); errors name the file and line.
absl::StatusOr<std::vector<SimFrame>> MakeSimPath(const std::string& file, const v1::Camera& base,
                                                  const std::vector<v1::NamedObject>& objects,
                                                  int frames, double rate);

}  // namespace aperture
