// The frame a command line asks for: the flags `aperture` and `aperture-render` share (--scene,
// --camera, --size, --aa, --filter, --mode, --compression, ...) and the one function that turns
// them into a v1::RenderFrameRequest. Proto only: the client links no engine code, and the engine
// turns the request into its settings (engine/frame/frame_job.h) the same way for the server and
// for aperture-render, so a frame rendered locally and one from the service are the same frame.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "absl/flags/declare.h"
#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "aperture/v1/render_service.pb.h"
#include "gltf_import.h"
#include "google/protobuf/descriptor.h"

ABSL_DECLARE_FLAG(std::string, scene);
ABSL_DECLARE_FLAG(std::string, camera);
ABSL_DECLARE_FLAG(double, fov);
ABSL_DECLARE_FLAG(double, near);
ABSL_DECLARE_FLAG(std::string, size);
ABSL_DECLARE_FLAG(std::string, region);
ABSL_DECLARE_FLAG(std::string, aa);
ABSL_DECLARE_FLAG(std::string, filter);
ABSL_DECLARE_FLAG(double, aperture);
ABSL_DECLARE_FLAG(std::string, mode);
ABSL_DECLARE_FLAG(double, delta);
ABSL_DECLARE_FLAG(int, max_depth);
ABSL_DECLARE_FLAG(std::string, compression);
ABSL_DECLARE_FLAG(bool, float_pixels);
ABSL_DECLARE_FLAG(bool, transparent_sky);
ABSL_DECLARE_FLAG(double, scene_time_s);
ABSL_DECLARE_FLAG(std::string, time);
ABSL_DECLARE_FLAG(std::string, place);
ABSL_DECLARE_FLAG(bool, light_points);
ABSL_DECLARE_FLAG(std::string, o);

namespace aperture {

// The command-line names of a proto enum's values, read from its descriptor: ANTI_ALIASING_BOX2
// is "box2" (the enum's common prefix dropped, lower case); the *_DEFAULT value has none.
std::vector<std::string> EnumFlagNames(const google::protobuf::EnumDescriptor& descriptor);

// The value a flag names, or an error naming the flag and listing the names it takes.
absl::StatusOr<int> EnumFromFlag(const google::protobuf::EnumDescriptor& descriptor,
                                 absl::string_view flag, absl::string_view name);

// "WIDTHxHEIGHT" (--size); each side a decimal number of at most nine digits.
absl::Status ParseSize(const std::string& text, uint32_t* width, uint32_t* height);

// "X,Y,Z,YAW,PITCH,ROLL" into `camera` (other fields, near and fov among them, kept).
absl::Status ParseCameraInto(const std::string& spec, v1::Camera* camera);

// The request the flags describe; the scene id is left to the caller. The camera: six numbers in
// --camera, else a glTF model's camera by that name (its first when --camera is empty), else the
// scene's own camera (`own`, a built-in scene's), else eye height at the origin.
// `both`: non-null in aperture-render, which also takes --mode both (raster, then raytrace); the
// request is then made for raytrace and *both is set.
absl::StatusOr<v1::RenderFrameRequest> FrameRequestFromFlags(
    const std::optional<v1::Camera>& own, const std::vector<GltfCamera>& model_cameras,
    bool* both = nullptr);

}  // namespace aperture
