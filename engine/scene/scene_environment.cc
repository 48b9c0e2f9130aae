#include "scene/scene_environment.h"

#include <cmath>

#include "absl/strings/str_cat.h"

namespace aperture {
namespace {

absl::Status Invalid(const std::string& where, const std::string& what) {
  return absl::InvalidArgumentError(absl::StrCat(where, ": ", what));
}

}  // namespace

absl::StatusOr<Rgba> ColorFromProto(const v1::Color& c, const std::string& where) {
  const float values[] = {c.r(), c.g(), c.b()};
  for (float v : values)
    if (!std::isfinite(v) || v < 0)
      return Invalid(where, "colour components must be finite and >= 0");
  return Rgba{c.r(), c.g(), c.b(), 1.0f};
}

absl::Status SetSun(const v1::Sun& sun, Scene* scene) {
  const Vec3 dir{sun.direction().x(), sun.direction().y(), sun.direction().z()};
  if (!IsFinite(dir)) return Invalid("sun.direction", "is not finite");
  if (Length(dir) == 0) return absl::OkStatus();
  auto c = ColorFromProto(sun.color(), "sun.color");
  if (!c.ok()) return c.status();
  scene->sun_direction = Normalize(dir);
  scene->sun_color = *c;
  return absl::OkStatus();
}

absl::Status SetAmbient(const v1::Color& ambient, Scene* scene) {
  auto c = ColorFromProto(ambient, "ambient");
  if (!c.ok()) return c.status();
  scene->ambient = *c;
  return absl::OkStatus();
}

absl::Status SetFog(const v1::Fog& fog, Scene* scene) {
  auto c = ColorFromProto(fog.color(), "fog.color");
  if (!c.ok()) return c.status();
  const double d = fog.density(), visibility = fog.visibility();
  if (!std::isfinite(d) || d < 0) return Invalid("fog.density", "must be finite and >= 0");
  if (!std::isfinite(visibility) || visibility < 0)
    return Invalid("fog.visibility", "must be finite and >= 0");
  if (d > 0 && visibility > 0) return Invalid("fog", "set density or visibility, not both");
  scene->fog_color = *c;
  // WMO's meteorological optical range: the distance over which contrast falls to 5 %,
  // exp(-density * visibility) = 0.05.
  scene->fog_density = visibility > 0 ? std::log(20.0) / visibility : d;
  return absl::OkStatus();
}

absl::Status SetSky(const v1::Color& sky, Scene* scene) {
  auto c = ColorFromProto(sky, "sky");
  if (!c.ok()) return c.status();
  scene->sky = *c;
  return absl::OkStatus();
}

}  // namespace aperture
