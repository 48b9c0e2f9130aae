#include "io/exr_header.h"

#include "absl/strings/str_format.h"

namespace aperture {

std::vector<ExrAttribute> HeaderAttributes(const ExrMetadata& m) {
  std::vector<ExrAttribute> out;
  auto text = [&](const char* name, const std::string& value) {
    if (!value.empty()) out.push_back({name, value, 0, false});
  };
  auto number = [&](const char* name, double value) {
    out.push_back({name, "", static_cast<float>(value), true});
  };
  text("aperture:scene", m.scene_name);
  text("aperture:camera", m.camera);
  text("aperture:mode", m.mode);
  number("aperture:setup_ms", m.setup_ms);
  number("aperture:raster_ms", m.raster_ms);
  number("aperture:render_ms", m.setup_ms + m.raster_ms);
  text("Software", "Aperture " APERTURE_VERSION);
  for (const auto& [key, value] : m.extra) text(key.c_str(), value);
  return out;
}

std::string CameraText(const Camera& c) {
  std::string text =
      absl::StrFormat("%g,%g,%g,%g,%g,%g fov=%g", c.position.x, c.position.y, c.position.z,
                      c.yaw_deg, c.pitch_deg, c.roll_deg, c.vertical_fov_deg);
  if (c.view_yaw_deg != 0 || c.view_pitch_deg != 0 || c.view_roll_deg != 0)
    text +=
        absl::StrFormat(" view_offset=%g,%g,%g", c.view_yaw_deg, c.view_pitch_deg, c.view_roll_deg);
  if (c.off_axis)
    text +=
        absl::StrFormat(" frustum=%g,%g,%g,%g", c.left_deg, c.right_deg, c.bottom_deg, c.top_deg);
  return text;
}

ExrMetadata FrameMetadata(const std::string& scene_name, const Camera& camera,
                          const RenderedFrame& frame, int frame_width, int frame_height,
                          const char* mode) {
  ExrMetadata m;
  m.scene_name = scene_name;
  m.camera = CameraText(camera);
  m.mode = mode;
  m.setup_ms = frame.stats.setup_ms;
  m.raster_ms = frame.stats.raster_ms;
  m.x = frame.region.x0;
  m.y = frame.region.y0;
  m.frame_width = frame_width;
  m.frame_height = frame_height;
  return m;
}

}  // namespace aperture
