#include "scene/light_points.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "absl/strings/str_cat.h"

namespace aperture {
namespace {

absl::Status Invalid(const std::string& where, const std::string& what) {
  return absl::InvalidArgumentError(absl::StrCat(where, ": ", what));
}

Vec3 FromProto(const v1::Vec3& v) { return {v.x(), v.y(), v.z()}; }

// The lights of a row: `count`, or as many as `spacing_m` fits from start to end.
absl::StatusOr<uint64_t> RowCount(const v1::LightRow& row, const std::string& where,
                                  uint64_t max_lights) {
  const Vec3 start = FromProto(row.start()), end = FromProto(row.end());
  if (!IsFinite(start)) return Invalid(where + ".start", "coordinate is NaN or infinite");
  if (!IsFinite(end)) return Invalid(where + ".end", "coordinate is NaN or infinite");
  if (row.count() > 0 && row.spacing_m() != 0)
    return Invalid(where, "set count or spacing_m, not both");
  if (row.count() > 0) return uint64_t{row.count()};
  if (!(row.spacing_m() > 0) || !std::isfinite(row.spacing_m()))
    return Invalid(where + ".spacing_m",
                   absl::StrCat("must be > 0 (or give count), is ", row.spacing_m()));
  const double lights = std::floor(Length(end - start) / row.spacing_m() + 1e-9) + 1;
  // With no limit a row still holds at most what its count could say (a uint32), so the count
  // converts exactly.
  constexpr uint64_t kMaxRowLights = UINT32_MAX;
  const uint64_t limit = max_lights > 0 ? std::min(max_lights, kMaxRowLights) : kMaxRowLights;
  if (lights > static_cast<double>(limit))
    return Invalid(where,
                   absl::StrCat("spacing_m ", row.spacing_m(), " over ", Length(end - start),
                                " m makes ", lights, " lights, above the limit of ", limit,
                                limit == max_lights ? " lights per scene" : " lights a row"));
  return static_cast<uint64_t>(lights);
}

// One light from its message; `where` names it in errors.
absl::StatusOr<PointLight> MakeLight(const v1::LightPoint& p, const std::string& where,
                                     const absl::flat_hash_map<std::string, size_t>& objects,
                                     SceneLights& out) {
  PointLight light;
  light.position = FromProto(p.position());
  if (!IsFinite(light.position))
    return Invalid(where + ".position", "coordinate is NaN or infinite");
  if (p.has_color()) {
    const v1::Color& c = p.color();
    if (!(c.r() >= 0 && c.g() >= 0 && c.b() >= 0) || !std::isfinite(c.r() + c.g() + c.b()))
      return Invalid(where + ".color", "components must be finite and >= 0");
    light.color = {c.r(), c.g(), c.b(), 1};
  }
  if (!(p.intensity_cd() > 0) || !std::isfinite(p.intensity_cd()))
    return Invalid(where + ".intensity_cd", absl::StrCat("must be > 0, is ", p.intensity_cd()));
  light.intensity_cd = p.intensity_cd();
  if (p.radius_m() != 0) {
    if (!(p.radius_m() > 0) || !std::isfinite(p.radius_m()))
      return Invalid(where + ".radius_m", absl::StrCat("must be > 0, is ", p.radius_m()));
    light.radius_m = p.radius_m();
  }
  if (p.has_lobe()) {
    const v1::LightLobe& l = p.lobe();
    const Vec3 axis = FromProto(l.axis());
    if (!IsFinite(axis) || !(Length(axis) > 0))
      return Invalid(where + ".lobe.axis", "must be a finite non-zero direction");
    for (auto [name, deg] : {std::pair{"horizontal_deg", l.horizontal_deg()},
                             std::pair{"vertical_deg", l.vertical_deg()}})
      if (!(deg > 0 && deg < 90))
        return Invalid(absl::StrCat(where, ".lobe.", name),
                       absl::StrCat("must be in (0, 90) degrees, is ", deg));
    if (!(l.back_fraction() >= 0 && l.back_fraction() <= 1))
      return Invalid(where + ".lobe.back_fraction",
                     absl::StrCat("must be in [0, 1], is ", l.back_fraction()));
    light.directional = true;
    light.lobe = {Normalize(axis), std::tan(Radians(l.horizontal_deg())),
                  std::tan(Radians(l.vertical_deg())), l.back_fraction()};
  }
  if (p.has_flash()) {
    const v1::LightFlash& f = p.flash();
    if (!(f.period_s() > 0) || !std::isfinite(f.period_s()))
      return Invalid(where + ".flash.period_s", absl::StrCat("must be > 0, is ", f.period_s()));
    if (!(f.on_s() > 0 && f.on_s() <= f.period_s()))
      return Invalid(where + ".flash.on_s",
                     absl::StrCat("must be in (0, period_s], is ", f.on_s()));
    if (!std::isfinite(f.phase_s())) return Invalid(where + ".flash.phase_s", "is not finite");
    light.flash = {f.period_s(), f.on_s(), f.phase_s()};
  }
  if (!p.group().empty()) {
    auto [it, added] = out.group_index.try_emplace(p.group(), out.groups.size());
    if (added) out.groups.push_back({p.group(), 1, true});
    light.group = static_cast<int>(it->second);
  }
  if (!p.object().empty()) {
    auto it = objects.find(p.object());
    if (it == objects.end())
      return absl::NotFoundError(
          absl::StrCat(where, ".object: '", p.object(), "' is not a named object of the scene"));
    light.object = static_cast<int>(it->second);
  }
  return light;
}

}  // namespace

absl::StatusOr<uint64_t> CountSceneLights(const v1::Scene& proto, uint64_t max_lights) {
  if (proto.spot_lights_size() > kMaxSpotLights)
    return absl::InvalidArgumentError(
        absl::StrCat("spot_lights: the scene has ", proto.spot_lights_size(),
                     ", above the budget of ", kMaxSpotLights, " spot lights per scene"));
  uint64_t lights = static_cast<uint64_t>(proto.lights_size() + proto.spot_lights_size());
  for (int i = 0; i < proto.light_rows_size(); ++i) {
    auto count = RowCount(proto.light_rows(i), absl::StrCat("light_rows[", i, "]"), max_lights);
    if (!count.ok()) return count.status();
    lights += *count;
  }
  if (max_lights > 0 && lights > max_lights)
    return absl::InvalidArgumentError(absl::StrCat("lights, light_rows: the scene makes ", lights,
                                                   " lights, above the limit of ", max_lights,
                                                   " lights per scene"));
  return lights;
}

absl::StatusOr<SceneLights> BuildSceneLights(
    const v1::Scene& proto, const absl::flat_hash_map<std::string, size_t>& object_index,
    uint64_t max_lights) {
  auto count = CountSceneLights(proto, max_lights);
  if (!count.ok()) return count.status();
  SceneLights out;
  out.lights.reserve(*count);
  const v1::LightSettings& s = proto.light_settings();
  if (s.exposure() != 0) {
    if (!(s.exposure() > 0) || !std::isfinite(s.exposure()))
      return Invalid("light_settings.exposure", absl::StrCat("must be > 0, is ", s.exposure()));
    out.settings.exposure = s.exposure();
  }
  if (s.min_size_px() != 0) {
    if (!(s.min_size_px() > 0 && s.min_size_px() <= 64))
      return Invalid("light_settings.min_size_px",
                     absl::StrCat("must be in (0, 64] pixels, is ", s.min_size_px()));
    out.settings.min_size_px = s.min_size_px();
  }
  if (s.surface_exposure() != 0) {
    if (!(s.surface_exposure() > 0) || !std::isfinite(s.surface_exposure()))
      return Invalid("light_settings.surface_exposure",
                     absl::StrCat("must be > 0, is ", s.surface_exposure()));
    out.settings.surface_exposure = s.surface_exposure();
  }
  for (int i = 0; i < proto.lights_size(); ++i) {
    auto light = MakeLight(proto.lights(i), absl::StrCat("lights[", i, "]"), object_index, out);
    if (!light.ok()) return light.status();
    out.lights.push_back(*std::move(light));
  }
  for (int i = 0; i < proto.light_rows_size(); ++i) {
    const v1::LightRow& row = proto.light_rows(i);
    const std::string where = absl::StrCat("light_rows[", i, "]");
    if (!std::isfinite(row.sequence_s())) return Invalid(where + ".sequence_s", "is not finite");
    auto n = RowCount(row, where, max_lights);
    if (!n.ok()) return n.status();
    auto light = MakeLight(row.light(), where + ".light", object_index, out);
    if (!light.ok()) return light.status();
    const Vec3 start = FromProto(row.start()), end = FromProto(row.end());
    // Spaced from the start; with a count, the last one at the end.
    const Vec3 step = row.count() > 0
                          ? (*n > 1 ? (end - start) * (1.0 / static_cast<double>(*n - 1)) : Vec3{})
                          : Normalize(end - start) * row.spacing_m();
    for (uint64_t k = 0; k < *n; ++k) {
      PointLight l = *light;
      l.position = start + step * static_cast<double>(k);
      l.flash.phase_s += row.sequence_s() * static_cast<double>(k);
      out.lights.push_back(l);
    }
  }
  for (int i = 0; i < proto.spot_lights_size(); ++i) {
    const std::string where = absl::StrCat("spot_lights[", i, "]");
    v1::LightPoint lamp;
    auto spot = MakeSpotLight(proto.spot_lights(i), where, object_index, &lamp);
    if (!spot.ok()) return spot.status();
    auto light = MakeLight(lamp, where, object_index, out);
    if (!light.ok()) return light.status();
    spot->group = light->group;
    spot->object = light->object;
    out.lights.push_back(*std::move(light));
    out.spots.push_back(*std::move(spot));
  }
  return out;
}

double LightIntensityTowards(const PointLight& light, const Vec3& to_eye, double time_s,
                             const std::vector<LightGroup>& groups) {
  double scale = 1;
  if (light.group >= 0) {
    const LightGroup& g = groups[light.group];
    if (!g.visible) return 0;
    scale = g.intensity_scale;
  }
  if (light.flash.period_s > 0) {
    const double t = std::fmod(time_s - light.flash.phase_s, light.flash.period_s);
    const double into = t < 0 ? t + light.flash.period_s : t;
    if (!(into < light.flash.on_s)) return 0;
  }
  double lobe = 1;
  if (light.directional) {
    // The lobe's frame: its axis, a horizontal right (from the frame's up, +y; +z for an axis
    // straight up or down) and the up that completes it.
    const Vec3& a = light.lobe.axis;
    const Vec3 up = std::abs(a.y) < 0.999 ? Vec3{0, 1, 0} : Vec3{0, 0, 1};
    const Vec3 right = Normalize(Cross(a, up));
    const Vec3 over = Cross(right, a);
    const double z = Dot(to_eye, a);
    double falloff = 0;
    if (z > 0) {
      const double h = Dot(to_eye, right) / z / light.lobe.tan_horizontal;
      const double v = Dot(to_eye, over) / z / light.lobe.tan_vertical;
      falloff = std::max(0.0, 1 - (h * h + v * v));
    }
    lobe = std::max(light.lobe.back_fraction, falloff);
  }
  return light.intensity_cd * scale * lobe;
}

}  // namespace aperture
