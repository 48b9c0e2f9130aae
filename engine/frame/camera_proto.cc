#include "frame/camera_proto.h"

namespace aperture {

absl::StatusOr<Camera> CameraFromProto(const v1::Camera& p) {
  Camera c;
  c.position = {p.position().x(), p.position().y(), p.position().z()};
  c.yaw_deg = p.yaw_deg();
  c.pitch_deg = p.pitch_deg();
  c.roll_deg = p.roll_deg();
  c.view_yaw_deg = p.view_offset().yaw_deg();
  c.view_pitch_deg = p.view_offset().pitch_deg();
  c.view_roll_deg = p.view_offset().roll_deg();
  if (p.vertical_fov_deg() != 0) c.vertical_fov_deg = p.vertical_fov_deg();
  if (p.has_frustum()) {
    c.off_axis = true;
    c.left_deg = p.frustum().left_deg();
    c.right_deg = p.frustum().right_deg();
    c.bottom_deg = p.frustum().bottom_deg();
    c.top_deg = p.frustum().top_deg();
  }
  if (p.near() != 0) c.near = p.near();
  c.far = p.far();
  if (auto s = ValidateCamera(c); !s.ok()) return s;
  return c;
}

v1::Camera CameraToProto(const Camera& c) {
  v1::Camera p;
  p.mutable_position()->set_x(c.position.x);
  p.mutable_position()->set_y(c.position.y);
  p.mutable_position()->set_z(c.position.z);
  p.set_yaw_deg(c.yaw_deg);
  p.set_pitch_deg(c.pitch_deg);
  p.set_roll_deg(c.roll_deg);
  if (c.view_yaw_deg != 0 || c.view_pitch_deg != 0 || c.view_roll_deg != 0) {
    p.mutable_view_offset()->set_yaw_deg(c.view_yaw_deg);
    p.mutable_view_offset()->set_pitch_deg(c.view_pitch_deg);
    p.mutable_view_offset()->set_roll_deg(c.view_roll_deg);
  }
  p.set_vertical_fov_deg(c.vertical_fov_deg);
  if (c.off_axis) {
    p.mutable_frustum()->set_left_deg(c.left_deg);
    p.mutable_frustum()->set_right_deg(c.right_deg);
    p.mutable_frustum()->set_bottom_deg(c.bottom_deg);
    p.mutable_frustum()->set_top_deg(c.top_deg);
  }
  p.set_near(c.near);
  p.set_far(c.far);
  return p;
}

}  // namespace aperture
