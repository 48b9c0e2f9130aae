#include "sim_path.h"

#include <google/protobuf/util/json_util.h>

#include <cmath>
#include <fstream>

#include "absl/strings/str_cat.h"
#include "absl/strings/strip.h"
#include "request_flags.h"

namespace aperture {
namespace {

constexpr double kCameraSpeed = 60;        // m/s along -z
constexpr double kObjectAcceleration = 2;  // m/s^2 along each object's heading

// A JSON line's camera over the base: what the line leaves unset comes from the command line.
v1::Camera CameraFromLine(const v1::Camera& line, const v1::Camera& base) {
  v1::Camera camera = line;
  if (camera.vertical_fov_deg() == 0 && !camera.has_frustum()) {
    camera.set_vertical_fov_deg(base.vertical_fov_deg());
    if (base.has_frustum()) *camera.mutable_frustum() = base.frustum();
  }
  if (camera.near() == 0) camera.set_near(base.near());
  if (camera.far() == 0) camera.set_far(base.far());
  return camera;
}

// Every named object `seconds` into a roll from standstill along its own heading (yaw 0 heads
// along -z, yaw 90 along -x).
v1::SceneUpdate RollForward(const std::vector<v1::NamedObject>& objects, double seconds) {
  v1::SceneUpdate update;
  const double distance = 0.5 * kObjectAcceleration * seconds * seconds;
  for (const v1::NamedObject& object : objects) {
    if (object.hidden()) continue;
    v1::ObjectUpdate& o = *update.add_objects();
    o.set_name(object.name());
    *o.mutable_transform() = object.transform();
    const double yaw = object.transform().yaw_deg() * M_PI / 180;
    v1::Vec3& t = *o.mutable_transform()->mutable_translation();
    t.set_x(t.x() - distance * std::sin(yaw));
    t.set_z(t.z() - distance * std::cos(yaw));
  }
  return update;
}

}  // namespace

absl::StatusOr<std::vector<SimFrame>> MakeSimPath(const std::string& file, const v1::Camera& base,
                                                  const std::vector<v1::NamedObject>& objects,
                                                  int frames, double rate) {
  std::vector<SimFrame> path;
  if (file.empty()) {
    for (int i = 0; i < frames; ++i) {
      const double seconds = i / rate;
      SimFrame frame{base, std::nullopt, seconds};
      frame.camera.mutable_position()->set_z(base.position().z() - kCameraSpeed * seconds);
      if (!objects.empty()) frame.update = RollForward(objects, seconds);
      path.push_back(std::move(frame));
    }
    return path;
  }
  std::ifstream in(file);
  if (!in) return absl::NotFoundError(absl::StrCat("cannot read --path ", file));
  std::string line;
  v1::Camera camera = base;
  for (int number = 1; std::getline(in, line) && static_cast<int>(path.size()) < frames; ++number) {
    const absl::string_view text = absl::StripAsciiWhitespace(line);
    if (text.empty() || text[0] == '#') continue;
    const std::string where = absl::StrCat(file, ":", number, ": ");
    SimFrame frame;
    frame.scene_time_s = static_cast<double>(path.size()) / rate;
    if (text[0] == '{') {
      v1::RenderFrameRequest request;
      google::protobuf::util::JsonParseOptions options;
      options.ignore_unknown_fields = false;
      if (auto s =
              google::protobuf::util::JsonStringToMessage(std::string(text), &request, options);
          !s.ok())
        return absl::InvalidArgumentError(absl::StrCat(where, std::string(s.message())));
      if (request.has_camera()) camera = CameraFromLine(request.camera(), base);
      if (request.has_update()) frame.update = request.update();
      if (request.scene_time_s() != 0) frame.scene_time_s = request.scene_time_s();
    } else if (auto s = ParseCameraInto(std::string(text), &camera); !s.ok()) {
      return absl::InvalidArgumentError(absl::StrCat(where, s.message()));
    }
    frame.camera = camera;
    path.push_back(std::move(frame));
  }
  if (path.empty())
    return absl::InvalidArgumentError(absl::StrCat("--path ", file, " has no frames"));
  return path;
}

}  // namespace aperture
