#include "request_flags.h"

#include <algorithm>
#include <cstdio>
#include <vector>

#include "absl/flags/flag.h"
#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_join.h"
#include "absl/strings/str_split.h"
#include "client_flags.h"

namespace aperture {

absl::Status ParseSize(const std::string& text, uint32_t* width, uint32_t* height) {
  std::vector<std::string> parts = absl::StrSplit(text, 'x');
  if (parts.size() != 2 || !absl::SimpleAtoi(parts[0], width) ||
      !absl::SimpleAtoi(parts[1], height))
    return absl::InvalidArgumentError(
        absl::StrCat("--size '", text, "' must be WIDTHxHEIGHT, e.g. 1920x1080"));
  return absl::OkStatus();
}

namespace {

absl::Status ParseRegion(const std::string& text, v1::PixelRegion* region) {
  std::vector<std::string> parts = absl::StrSplit(text, ',');
  uint32_t x = 0, y = 0, w = 0, h = 0;
  if (parts.size() != 3 || !absl::SimpleAtoi(parts[0], &x) || !absl::SimpleAtoi(parts[1], &y) ||
      !ParseSize(parts[2], &w, &h).ok())
    return absl::InvalidArgumentError(
        absl::StrCat("--region '", text, "' must be X,Y,WIDTHxHEIGHT, e.g. 0,0,64x64"));
  region->set_x(x);
  region->set_y(y);
  region->set_width(w);
  region->set_height(h);
  return absl::OkStatus();
}

template <typename Enum>
absl::StatusOr<Enum> Lookup(const char* flag, const std::string& name,
                            std::initializer_list<std::pair<const char*, Enum>> table) {
  std::string names;
  for (const auto& [key, value] : table) {
    if (name == key) return value;
    absl::StrAppend(&names, names.empty() ? "" : ", ", key);
  }
  return absl::InvalidArgumentError(
      absl::StrCat("--", flag, " '", name, "' is not one of ", names));
}

}  // namespace

absl::Status ParseCameraInto(const std::string& spec, v1::Camera* camera) {
  std::vector<std::string> parts = absl::StrSplit(spec, ',');
  double v[6];
  bool ok = parts.size() == 6;
  for (size_t i = 0; ok && i < 6; ++i) ok = absl::SimpleAtod(parts[i], &v[i]);
  if (!ok)
    return absl::InvalidArgumentError(
        absl::StrCat("camera '", spec, "' must be X,Y,Z,YAW,PITCH,ROLL (six numbers)"));
  camera->mutable_position()->set_x(v[0]);
  camera->mutable_position()->set_y(v[1]);
  camera->mutable_position()->set_z(v[2]);
  camera->set_yaw_deg(v[3]);
  camera->set_pitch_deg(v[4]);
  camera->set_roll_deg(v[5]);
  return absl::OkStatus();
}

absl::StatusOr<v1::RenderFrameRequest> FrameRequestFromFlags(const SceneOnServer& scene) {
  v1::RenderFrameRequest request;
  request.set_scene_id(scene.scene_id);

  v1::Camera& camera = *request.mutable_camera();
  if (scene.default_camera) {
    camera = *scene.default_camera;
  } else {
    camera.mutable_position()->set_y(1.7);
    camera.set_near(0.1);
  }
  // Six numbers place the camera; else a glTF model's camera by name, its first by default (as in
  // aperture-render).
  const std::string spec = absl::GetFlag(FLAGS_camera);
  bool model_camera = false;
  if (!spec.empty() && ParseCameraInto(spec, &camera).ok()) {
    // placed by the numbers
  } else if (const auto named =
                 std::find_if(scene.model_cameras.begin(), scene.model_cameras.end(),
                              [&](const GltfCamera& c) { return spec.empty() || c.name == spec; });
             named != scene.model_cameras.end()) {
    camera = named->camera;
    model_camera = true;
  } else if (!spec.empty() && scene.model_cameras.empty()) {
    return ParseCameraInto(spec, &camera);  // says what the six numbers should be
  } else if (!spec.empty()) {
    std::vector<std::string> names;
    for (const GltfCamera& c : scene.model_cameras) names.push_back(c.name);
    return absl::InvalidArgumentError(
        absl::StrCat("--camera '", spec,
                     "' is neither X,Y,Z,YAW,PITCH,ROLL nor a camera of the "
                     "model (",
                     absl::StrJoin(names, ", "), ")"));
  }
  if (const double fov = absl::GetFlag(FLAGS_fov); fov != 0)
    camera.set_vertical_fov_deg(fov);
  else if (!model_camera)
    camera.set_vertical_fov_deg(60);
  if (absl::GetFlag(FLAGS_near) != 0) camera.set_near(absl::GetFlag(FLAGS_near));

  v1::RenderOptions& options = *request.mutable_options();
  uint32_t width = 0, height = 0;
  if (auto s = ParseSize(absl::GetFlag(FLAGS_size), &width, &height); !s.ok()) return s;
  options.set_width(width);
  options.set_height(height);
  if (const std::string region = absl::GetFlag(FLAGS_region); !region.empty())
    if (auto s = ParseRegion(region, request.mutable_region()); !s.ok()) return s;

  auto aa = Lookup<v1::AntiAliasing>("aa", absl::GetFlag(FLAGS_aa),
                                     {{"box2", v1::ANTI_ALIASING_BOX2},
                                      {"box1", v1::ANTI_ALIASING_BOX1},
                                      {"tent2", v1::ANTI_ALIASING_TENT2}});
  if (!aa.ok()) return aa.status();
  options.set_anti_aliasing(*aa);
  if (const std::string f = absl::GetFlag(FLAGS_filter); !f.empty()) {
    auto filter = Lookup<v1::TextureFilter>("filter", f,
                                            {{"nearest", v1::TEXTURE_FILTER_NEAREST},
                                             {"bilinear", v1::TEXTURE_FILTER_BILINEAR},
                                             {"trilinear", v1::TEXTURE_FILTER_TRILINEAR},
                                             {"aniso", v1::TEXTURE_FILTER_ANISO},
                                             {"oiio", v1::TEXTURE_FILTER_OIIO},
                                             {"reference", v1::TEXTURE_FILTER_REFERENCE}});
    if (!filter.ok()) return filter.status();
    options.set_filter(*filter);
  }
  options.set_texture_aperture(absl::GetFlag(FLAGS_aperture));
  auto mode = Lookup<v1::RenderMode>(
      "mode", absl::GetFlag(FLAGS_mode),
      {{"raster", v1::RENDER_MODE_RASTER}, {"raytrace", v1::RENDER_MODE_RAYTRACE}});
  if (!mode.ok()) return mode.status();
  options.set_mode(*mode);
  if (*mode == v1::RENDER_MODE_RAYTRACE) {
    // The server checks the ranges and names the field; here only what it cannot see.
    options.set_raytrace_delta(absl::GetFlag(FLAGS_delta));
    const int depth = absl::GetFlag(FLAGS_max_depth);
    if (depth < 0) return absl::InvalidArgumentError("--max_depth must be 0..8");
    options.mutable_raytrace_max_depth()->set_value(static_cast<uint32_t>(depth));
  }
  auto compression = Lookup<v1::ExrCompression>("compression", absl::GetFlag(FLAGS_compression),
                                                {{"none", v1::EXR_COMPRESSION_NONE},
                                                 {"rle", v1::EXR_COMPRESSION_RLE},
                                                 {"zips", v1::EXR_COMPRESSION_ZIPS},
                                                 {"zip", v1::EXR_COMPRESSION_ZIP},
                                                 {"piz", v1::EXR_COMPRESSION_PIZ},
                                                 {"dwaa", v1::EXR_COMPRESSION_DWAA}});
  if (!compression.ok()) return compression.status();
  options.set_compression(*compression);
  options.set_pixel_type(absl::GetFlag(FLAGS_float_pixels) ? v1::PIXEL_TYPE_FLOAT
                                                           : v1::PIXEL_TYPE_HALF);
  options.set_transparent_sky(absl::GetFlag(FLAGS_transparent_sky));
  return request;
}

}  // namespace aperture
