// The scene's light and air from their proto form: sun, ambient, fog and sky colour. One set of
// rules (and error messages) for a scene being built and for a live frame's update.
#pragma once

#include <string>

#include "absl/status/statusor.h"
#include "aperture/v1/scene.pb.h"
#include "scene/scene.h"

namespace aperture {

// A linear colour (alpha 1); its components must be finite and >= 0, else an error naming `where`.
absl::StatusOr<Rgba> ColorFromProto(const v1::Color& c, const std::string& where);

// Each sets the scene's value from the proto after validating it (errors name the field);
// on error the scene is unchanged.
absl::Status SetSun(const v1::Sun& sun, Scene* scene);  // a zero direction leaves the sun as is
absl::Status SetAmbient(const v1::Color& ambient, Scene* scene);
absl::Status SetFog(const v1::Fog& fog, Scene* scene);  // density, or visibility
absl::Status SetSky(const v1::Color& sky, Scene* scene);

}  // namespace aperture
