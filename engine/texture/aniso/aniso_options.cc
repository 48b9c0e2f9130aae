#include "texture/aniso/aniso_options.h"

#include <cmath>
#include <vector>

#include "absl/strings/ascii.h"
#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_join.h"
#include "absl/strings/str_split.h"

namespace aperture {
namespace {

struct FloatField {
  const char* name;
  float AnisoOptions::*field;
  float lo, hi;  // the valid range, both ends included
};
constexpr FloatField kFloatFields[] = {
    {"axis_blend_zone", &AnisoOptions::axis_blend_zone, 0.0f, 0.5f},
    {"copy_extent_scale", &AnisoOptions::copy_extent_scale, 0.0f, 1.0f},
    {"probe_half_extent", &AnisoOptions::probe_half_extent, 0.5f, 4.0f},
    {"box_probe_thickness", &AnisoOptions::box_probe_thickness, 1.0f, 2.0f},
    {"box_probe_fade", &AnisoOptions::box_probe_fade, 1.0f, 1024.0f},
    {"taps_fade", &AnisoOptions::taps_fade, 1.0f, 1024.0f},
};
struct BoolField {
  const char* name;
  bool AnisoOptions::*field;
};
constexpr BoolField kBoolFields[] = {
    {"magnified_taps", &AnisoOptions::magnified_taps},
    {"principal_axes", &AnisoOptions::principal_axes},
    {"base_probes", &AnisoOptions::base_probes},
    {"box_probes", &AnisoOptions::box_probes},
    {"end_tilts_beyond_period", &AnisoOptions::end_tilts_beyond_period},
};

}  // namespace

absl::Status AnisoOptions::Validate() const {
  for (const FloatField& f : kFloatFields) {
    const float x = this->*f.field;
    if (!(x >= f.lo && x <= f.hi))
      return absl::InvalidArgumentError(
          absl::StrCat("aniso option ", f.name, " = ", x, " is outside [", f.lo, ", ", f.hi, "]"));
  }
  return absl::OkStatus();
}

absl::StatusOr<AnisoOptions> AnisoOptions::Parse(absl::string_view text) {
  AnisoOptions o;
  for (absl::string_view item : absl::StrSplit(text, ',', absl::SkipWhitespace())) {
    item = absl::StripAsciiWhitespace(item);
    const std::vector<absl::string_view> kv = absl::StrSplit(item, absl::MaxSplits('=', 1));
    if (kv.size() != 2)
      return absl::InvalidArgumentError(
          absl::StrCat("aniso option '", item, "': expected NAME=VALUE"));
    bool known = false;
    for (const FloatField& f : kFloatFields) {
      if (kv[0] != f.name) continue;
      known = true;
      if (!absl::SimpleAtof(kv[1], &(o.*f.field)))
        return absl::InvalidArgumentError(
            absl::StrCat("aniso option ", f.name, ": '", kv[1], "' is not a number"));
    }
    for (const BoolField& f : kBoolFields) {
      if (kv[0] != f.name) continue;
      known = true;
      if (!absl::SimpleAtob(kv[1], &(o.*f.field)))
        return absl::InvalidArgumentError(
            absl::StrCat("aniso option ", f.name, ": '", kv[1], "' is not true or false"));
    }
    if (!known) {
      std::vector<std::string> names;
      for (const FloatField& f : kFloatFields) names.push_back(f.name);
      for (const BoolField& f : kBoolFields) names.push_back(f.name);
      return absl::InvalidArgumentError(absl::StrCat(
          "unknown aniso option '", kv[0], "' (known: ", absl::StrJoin(names, ", "), ")"));
    }
  }
  if (absl::Status s = o.Validate(); !s.ok()) return s;
  return o;
}

std::string AnisoOptions::ChangedFields() const {
  const AnisoOptions defaults;
  std::vector<std::string> changed;
  for (const FloatField& f : kFloatFields)
    if (this->*f.field != defaults.*f.field)
      changed.push_back(absl::StrCat(f.name, "=", this->*f.field));
  for (const BoolField& f : kBoolFields)
    if (this->*f.field != defaults.*f.field)
      changed.push_back(absl::StrCat(f.name, "=", this->*f.field ? "true" : "false"));
  return absl::StrJoin(changed, ",");
}

}  // namespace aperture
