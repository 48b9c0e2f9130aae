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
  scene->sky_dome.analytic = false;
  return absl::OkStatus();
}

absl::Status SetTimeOfDay(const v1::TimeOfDay& proto, bool update, const std::string& where,
                          Scene* scene) {
  SceneTimeOfDay t;
  if (scene->time_of_day) t = *scene->time_of_day;
  const bool known = update && scene->time_of_day.has_value();
  if (!proto.utc().empty()) {
    auto utc = ParseUtc(proto.utc(), where + ".utc");
    if (!utc.ok()) return utc.status();
    t.utc = *utc;
  } else if (update && !t.utc) {
    return Invalid(where + ".utc", "the scene has no time of day yet: set its date and time");
  }
  if (proto.has_place() || !known) {
    if (!proto.has_place())
      return Invalid(where + ".place",
                     update ? "the scene has no place yet: set its latitude and longitude"
                            : "is unset: set the latitude and longitude");
    t.place = {proto.place().latitude_deg(), proto.place().longitude_deg()};
    if (auto s = ValidatePlace(t.place, where + ".place"); !s.ok()) return s;
  }
  const double turbidity = proto.turbidity();
  if (!std::isfinite(turbidity) || (turbidity != 0 && (turbidity < 2 || turbidity > 10)))
    return Invalid(where + ".turbidity",
                   absl::StrCat("must be within 2..10 (0: ", update ? "the scene's" : "3", "), is ",
                                turbidity));
  if (turbidity != 0) t.options.turbidity = turbidity;
  if (!update) {
    const double north = proto.grid_north_deg();
    if (!std::isfinite(north) || north < -360 || north > 360)
      return Invalid(where + ".grid_north_deg",
                     absl::StrCat("must be within [-360, 360], is ", north));
    t.options.grid_north_deg = north;
  }
  scene->time_of_day = t;
  ApplyDaylight(scene);
  return absl::OkStatus();
}

void ApplyDaylight(Scene* scene) {
  if (!scene->time_of_day || !scene->time_of_day->utc) return;
  const SceneTimeOfDay& t = *scene->time_of_day;
  const Daylight d = DaylightAt(*t.utc, t.place, t.options);
  scene->sun_direction = d.sun_direction;
  scene->sun_color = d.sun_color;
  scene->ambient = d.ambient;
  scene->fog_color = d.fog_color;
  scene->sky = d.sky;
  scene->sky_dome = d.dome;
}

}  // namespace aperture
