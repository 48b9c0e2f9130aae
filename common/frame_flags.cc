#include "frame_flags.h"

#include <algorithm>
#include <cctype>

#include "absl/flags/flag.h"
#include "absl/strings/ascii.h"
#include "absl/strings/match.h"
#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_join.h"
#include "absl/strings/str_split.h"

namespace aperture {
namespace {

// ANTI_ALIASING_ for AntiAliasing: the DEFAULT value's name without DEFAULT.
std::string ValuePrefix(const google::protobuf::EnumDescriptor& descriptor) {
  for (int i = 0; i < descriptor.value_count(); ++i) {
    const std::string& name = descriptor.value(i)->name();
    if (absl::EndsWith(name, "_DEFAULT")) return name.substr(0, name.size() - 7);
  }
  return "";
}

// "box1, box2, tent2": the names a flag of this enum takes, for its help and its errors.
std::string NameList(const google::protobuf::EnumDescriptor* descriptor) {
  return absl::StrJoin(EnumFlagNames(*descriptor), ", ");
}

}  // namespace
}  // namespace aperture

// The lists of names in the help are read from the proto's enums, so the help cannot drift from
// what the parser accepts.
ABSL_FLAG(
    std::string, scene, "airport",
    "'airport' (built-in: a real airport's map, buildings, cut-out trees), 'night' (that "
    "airport at night: runway, approach and taxiway lights, a lit town, 16 aircraft with "
    "their own lights), 'night-by-day' (the same by day, without its lights: the night's load "
    "to compare), 'demo' (the benchmarks' synthetic airfield), 'triangles' (10,000 "
    "random triangles), 'skewed' (a city block in one corner of the view), 'tris-N' (N "
    "triangles painted in order, the peer benchmark's), 'slivers-N' (N slivers on 13 "
    "planes, the service tests' slow frame), a scene JSON file or a glTF 2.0 model (.gltf, "
    ".glb)");
ABSL_FLAG(std::string, camera, "",
          "X,Y,Z,YAW,PITCH,ROLL, or the name of a glTF model's camera; default: a built-in "
          "scene's approach camera, a glTF model's first camera, else 0,1.7,0,0,0,0");
ABSL_FLAG(
    double, fov, 0,
    "vertical field of view, degrees; 0: the scene's camera's own (a built-in scene's, a glTF "
    "model camera's), else 60");
ABSL_FLAG(double, near, 0, "near plane distance (0: a built-in scene's camera's, else 0.1)");
ABSL_FLAG(std::string, size, "1920x1080", "image size WIDTHxHEIGHT (each 1..16384)");
ABSL_FLAG(std::string, region, "",
          "only this part of the frame, X,Y,WIDTHxHEIGHT; the EXR's data window, inside the "
          "display window of the whole frame");
ABSL_FLAG(std::string, aa, "box2",
          absl::StrCat("edge anti-aliasing: ",
                       aperture::NameList(aperture::v1::AntiAliasing_descriptor()),
                       " (box2: the 2x2 box of seed 002, box1: the pixel box, tent2: the tent "
                       "over 2x2)"));
ABSL_FLAG(std::string, filter, "",
          absl::StrCat("texture filter for every material: ",
                       aperture::NameList(aperture::v1::TextureFilter_descriptor()),
                       " (aniso: seed 000's tables, oiio: OpenImageIO's TextureSystem, reference: "
                       "dense supersampling); default: each material's own"));
ABSL_FLAG(double, aperture, 2, "texture filter aperture in pixels (1: pixel, 2: 2x2 square)");
ABSL_FLAG(std::string, mode, "raster",
          absl::StrCat("how the frame is made: ",
                       aperture::NameList(aperture::v1::RenderMode_descriptor()),
                       "; raster: Warnock windows with seed 002's exact edges, raytrace: seed "
                       "003's corner rays and texture integrals over each pixel's projection (the "
                       "only mode that draws spheres and cylinders); aperture-render also takes "
                       "both (raster, then raytrace; the raytraced frame goes next to -o with a "
                       "-raytrace suffix)"));
ABSL_FLAG(double, delta, 0.1,
          "with --mode raytrace, the allowed relative area error of the pixel-projection "
          "fragments (seed 003, eq. 9)");
ABSL_FLAG(int, max_depth, 3,
          "with --mode raytrace, the subdivisions of a pixel whose corner rays disagree (0..8)");
ABSL_FLAG(std::string, compression, "",
          absl::StrCat("EXR compression: ",
                       aperture::NameList(aperture::v1::ExrCompression_descriptor()),
                       "; empty: zip (aperture sim from a server across a network: b44a)"));
ABSL_FLAG(bool, float_pixels, false, "32-bit float channels instead of half");
ABSL_FLAG(bool, transparent_sky, false,
          "leave the sky transparent: alpha is what the scene covers, the colour premultiplied by "
          "it (for compositing the frame over other imagery)");
ABSL_FLAG(double, scene_time_s, 0,
          "the scene's clock, seconds: which flashing light points are on (LightFlash)");
ABSL_FLAG(std::string, time, "",
          "the time of day, ISO 8601 with its offset (2026-06-21T12:00Z): the sun, sky, ambient "
          "light and fog colour follow the hour at the scene's place (the built-in airport's is "
          "Schiphol) or --place's (docs/SCENE.md, \"Time of day\")");
ABSL_FLAG(std::string, place, "",
          "LATITUDE,LONGITUDE in degrees (north and east positive) for --time, over the scene's");
ABSL_FLAG(bool, light_points, true,
          "draw the scene's light points; false: the frame without them (to compare their cost)");
ABSL_FLAG(std::string, o, "frame.exr", "output EXR path (aperture batch: an output directory)");

namespace aperture {

std::vector<std::string> EnumFlagNames(const google::protobuf::EnumDescriptor& descriptor) {
  const std::string prefix = ValuePrefix(descriptor);
  std::vector<std::string> names;
  for (int i = 0; i < descriptor.value_count(); ++i) {
    const std::string& name = descriptor.value(i)->name();
    if (!absl::StartsWith(name, prefix) || absl::EndsWith(name, "_DEFAULT")) continue;
    names.push_back(absl::AsciiStrToLower(name.substr(prefix.size())));
  }
  return names;
}

absl::StatusOr<int> EnumFromFlag(const google::protobuf::EnumDescriptor& descriptor,
                                 absl::string_view flag, absl::string_view name) {
  const std::vector<std::string> names = EnumFlagNames(descriptor);
  const auto found = std::find(names.begin(), names.end(), name);
  if (found == names.end())
    return absl::InvalidArgumentError(
        absl::StrCat("--", flag, " '", name, "' is not one of ", absl::StrJoin(names, ", ")));
  // The value's full name is the prefix and the upper-case flag name.
  return descriptor
      .FindValueByName(absl::StrCat(ValuePrefix(descriptor), absl::AsciiStrToUpper(name)))
      ->number();
}

absl::Status ParseSize(const std::string& text, uint32_t* width, uint32_t* height) {
  std::vector<std::string> parts = absl::StrSplit(text, 'x');
  const auto number = [](const std::string& s, uint32_t* out) {
    return !s.empty() && s.size() <= 9 &&
           std::all_of(s.begin(), s.end(), [](char c) { return std::isdigit(c); }) &&
           absl::SimpleAtoi(s, out);
  };
  if (parts.size() != 2 || !number(parts[0], width) || !number(parts[1], height))
    return absl::InvalidArgumentError(
        absl::StrCat("--size '", text, "' must be WIDTHxHEIGHT, e.g. 1920x1080"));
  return absl::OkStatus();
}

absl::Status ParseCameraInto(const std::string& spec, v1::Camera* camera) {
  std::vector<std::string> parts = absl::StrSplit(spec, ',');
  double v[6];
  bool ok = parts.size() == 6;
  // NaN and infinities parse: the engine's camera check refuses them and names the field.
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

// The camera: six numbers, a model's camera by name (its first by default), or the scene's own.
absl::Status CameraFromFlags(const std::optional<v1::Camera>& own,
                             const std::vector<GltfCamera>& model_cameras, v1::Camera* camera) {
  if (own) {
    *camera = *own;
  } else {
    camera->mutable_position()->set_y(1.7);
    camera->set_near(0.1);
  }
  const std::string spec = absl::GetFlag(FLAGS_camera);
  bool model_camera = false;
  if (!spec.empty() && ParseCameraInto(spec, camera).ok()) {
    // placed by the numbers
  } else if (const auto named =
                 std::find_if(model_cameras.begin(), model_cameras.end(),
                              [&](const GltfCamera& c) { return spec.empty() || c.name == spec; });
             named != model_cameras.end()) {
    *camera = named->camera;
    model_camera = true;
  } else if (!spec.empty() && model_cameras.empty()) {
    return ParseCameraInto(spec, camera);  // says what the six numbers should be
  } else if (!spec.empty()) {
    std::vector<std::string> names;
    for (const GltfCamera& c : model_cameras) names.push_back(c.name);
    return absl::InvalidArgumentError(
        absl::StrCat("--camera '", spec, "' is neither X,Y,Z,YAW,PITCH,ROLL nor a camera of the ",
                     "model (", absl::StrJoin(names, ", "), ")"));
  }
  if (const double fov = absl::GetFlag(FLAGS_fov); fov != 0)
    camera->set_vertical_fov_deg(fov);
  else if (!model_camera && !(own && own->vertical_fov_deg() > 0))
    camera->set_vertical_fov_deg(60);
  if (absl::GetFlag(FLAGS_near) != 0) camera->set_near(absl::GetFlag(FLAGS_near));
  return absl::OkStatus();
}

// --time and --place into the request's scene update (the engine checks the values and names
// the field; here only the form of --place).
absl::Status TimeOfDayFromFlags(v1::RenderFrameRequest* request) {
  const std::string time = absl::GetFlag(FLAGS_time), place = absl::GetFlag(FLAGS_place);
  if (time.empty() && place.empty()) return absl::OkStatus();
  v1::TimeOfDay& t = *request->mutable_update()->mutable_time_of_day();
  t.set_utc(time);
  if (place.empty()) return absl::OkStatus();
  const std::vector<std::string> parts = absl::StrSplit(place, ',');
  double lat = 0, lon = 0;
  if (parts.size() != 2 || !absl::SimpleAtod(parts[0], &lat) || !absl::SimpleAtod(parts[1], &lon))
    return absl::InvalidArgumentError(
        absl::StrCat("--place '", place, "' is not LATITUDE,LONGITUDE (e.g. 52.31,4.76)"));
  t.mutable_place()->set_latitude_deg(lat);
  t.mutable_place()->set_longitude_deg(lon);
  return absl::OkStatus();
}

}  // namespace

absl::StatusOr<v1::RenderFrameRequest> FrameRequestFromFlags(
    const std::optional<v1::Camera>& own, const std::vector<GltfCamera>& model_cameras,
    bool* both) {
  v1::RenderFrameRequest request;
  if (auto s = CameraFromFlags(own, model_cameras, request.mutable_camera()); !s.ok()) return s;

  v1::RenderOptions& options = *request.mutable_options();
  uint32_t width = 0, height = 0;
  if (auto s = ParseSize(absl::GetFlag(FLAGS_size), &width, &height); !s.ok()) return s;
  options.set_width(width);
  options.set_height(height);
  if (const std::string region = absl::GetFlag(FLAGS_region); !region.empty())
    if (auto s = ParseRegion(region, request.mutable_region()); !s.ok()) return s;

  auto aa = EnumFromFlag(*v1::AntiAliasing_descriptor(), "aa", absl::GetFlag(FLAGS_aa));
  if (!aa.ok()) return aa.status();
  options.set_anti_aliasing(static_cast<v1::AntiAliasing>(*aa));
  if (const std::string f = absl::GetFlag(FLAGS_filter); !f.empty()) {
    auto filter = EnumFromFlag(*v1::TextureFilter_descriptor(), "filter", f);
    if (!filter.ok()) return filter.status();
    options.set_filter(static_cast<v1::TextureFilter>(*filter));
  }
  options.set_texture_aperture(absl::GetFlag(FLAGS_aperture));

  const std::string mode_name = absl::GetFlag(FLAGS_mode);
  if (both) *both = mode_name == "both";
  auto mode = both && *both ? absl::StatusOr<int>(v1::RENDER_MODE_RAYTRACE)
                            : EnumFromFlag(*v1::RenderMode_descriptor(), "mode", mode_name);
  if (!mode.ok())
    return both ? absl::InvalidArgumentError(absl::StrCat(mode.status().message(), ", both"))
                : mode.status();
  options.set_mode(static_cast<v1::RenderMode>(*mode));
  if (*mode == v1::RENDER_MODE_RAYTRACE) {
    // The engine checks the ranges and names the field; here only what it cannot see.
    options.set_raytrace_delta(absl::GetFlag(FLAGS_delta));
    const int depth = absl::GetFlag(FLAGS_max_depth);
    if (depth < 0) return absl::InvalidArgumentError("--max_depth must be 0..8");
    options.mutable_raytrace_max_depth()->set_value(static_cast<uint32_t>(depth));
  }

  // Unset: EXR_COMPRESSION_DEFAULT, zip, unless the command chooses (aperture sim's remote one).
  if (const std::string c = absl::GetFlag(FLAGS_compression); !c.empty()) {
    auto compression = EnumFromFlag(*v1::ExrCompression_descriptor(), "compression", c);
    if (!compression.ok()) return compression.status();
    options.set_compression(static_cast<v1::ExrCompression>(*compression));
  }
  options.set_pixel_type(absl::GetFlag(FLAGS_float_pixels) ? v1::PIXEL_TYPE_FLOAT
                                                           : v1::PIXEL_TYPE_HALF);
  options.set_transparent_sky(absl::GetFlag(FLAGS_transparent_sky));
  options.set_hide_light_points(!absl::GetFlag(FLAGS_light_points));
  request.set_scene_time_s(absl::GetFlag(FLAGS_scene_time_s));
  if (auto s = TimeOfDayFromFlags(&request); !s.ok()) return s;
  return request;
}

}  // namespace aperture
