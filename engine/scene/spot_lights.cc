#include "scene/spot_lights.h"

#include "absl/strings/str_cat.h"

namespace aperture {
namespace {

absl::Status Invalid(const std::string& where, const std::string& what) {
  return absl::InvalidArgumentError(absl::StrCat(where, ": ", what));
}

Vec3 FromProto(const v1::Vec3& v) { return {v.x(), v.y(), v.z()}; }

void SetVec(v1::Vec3* out, const Vec3& v) {
  out->set_x(v.x);
  out->set_y(v.y);
  out->set_z(v.z);
}

}  // namespace

absl::StatusOr<SpotLight> MakeSpotLight(const v1::SpotLight& spot, const std::string& where,
                                        const absl::flat_hash_map<std::string, size_t>& objects,
                                        v1::LightPoint* lamp) {
  SpotLight out;
  out.position = FromProto(spot.position());
  if (!IsFinite(out.position)) return Invalid(where + ".position", "coordinate is NaN or infinite");
  const Vec3 direction = FromProto(spot.direction());
  if (!IsFinite(direction) || !(Length(direction) > 0))
    return Invalid(where + ".direction", "must be a finite non-zero direction");
  out.axis = Normalize(direction);
  if (!(spot.intensity_cd() > 0) || !std::isfinite(spot.intensity_cd()))
    return Invalid(where + ".intensity_cd",
                   absl::StrCat("must be > 0 candela, is ", spot.intensity_cd()));
  out.intensity_cd = spot.intensity_cd();
  if (!(spot.outer_deg() > 0 && spot.outer_deg() < 90))
    return Invalid(where + ".outer_deg",
                   absl::StrCat("must be in (0, 90) degrees, is ", spot.outer_deg()));
  if (!(spot.inner_deg() >= 0 && spot.inner_deg() <= spot.outer_deg()))
    return Invalid(where + ".inner_deg",
                   absl::StrCat("must be in [0, outer_deg] = [0, ", spot.outer_deg(),
                                "] degrees, is ", spot.inner_deg()));
  out.cos_inner = std::cos(Radians(spot.inner_deg()));
  out.cos_outer = std::cos(Radians(spot.outer_deg()));
  if (spot.has_color()) {
    const v1::Color& c = spot.color();
    if (!(c.r() >= 0 && c.g() >= 0 && c.b() >= 0) || !std::isfinite(c.r() + c.g() + c.b()))
      return Invalid(where + ".color", "components must be finite and >= 0");
    out.color = {c.r(), c.g(), c.b(), 1};
  }
  if (!spot.object().empty() && !objects.contains(spot.object()))
    return absl::NotFoundError(
        absl::StrCat(where, ".object: '", spot.object(), "' is not a named object of the scene"));
  if (spot.radius_m() != 0 && (!(spot.radius_m() > 0) || !std::isfinite(spot.radius_m())))
    return Invalid(where + ".radius_m", absl::StrCat("must be > 0, is ", spot.radius_m()));

  lamp->Clear();
  *lamp->mutable_position() = spot.position();
  if (spot.has_color()) *lamp->mutable_color() = spot.color();
  lamp->set_intensity_cd(spot.intensity_cd());
  SetVec(lamp->mutable_lobe()->mutable_axis(), out.axis);
  lamp->mutable_lobe()->set_horizontal_deg(spot.outer_deg());
  lamp->mutable_lobe()->set_vertical_deg(spot.outer_deg());
  lamp->set_group(spot.group());
  lamp->set_object(spot.object());
  lamp->set_radius_m(spot.radius_m());
  return out;
}

}  // namespace aperture
