// The scene's light and air from their proto form: sun, ambient, fog, sky colour and time of day.
// One set of rules (and error messages) for a scene being built and for a live frame's update.
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
absl::Status SetFog(const v1::Fog& fog, Scene* scene);    // density, or visibility
absl::Status SetSky(const v1::Color& sky, Scene* scene);  // one colour in every direction

// The scene's hour and place (docs/SCENE.md, "Time of day"): its sun, ambient, sky and fog colour
// follow from them. A scene's TimeOfDay needs its place (its time may come with a later update);
// an update's (`update` true) keeps the scene's for what it leaves unset. Errors name the field
// under `where`
// ("time_of_day.place.latitude_deg: ...").
absl::Status SetTimeOfDay(const v1::TimeOfDay& time_of_day, bool update, const std::string& where,
                          Scene* scene);

// While a scene has a time of day, its sun, ambient, sky and fog colour are the hour's, whatever
// else set them: this sets them again from Scene::time_of_day (nothing without a time and place).
void ApplyDaylight(Scene* scene);

}  // namespace aperture
