#include "scene/airport_lighting.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "absl/strings/str_cat.h"

namespace aperture {
namespace {

double Degrees(double radians) { return radians * (180.0 / kPi); }

constexpr Vec3 kUp{0, 1, 0};

// --- Colours -------------------------------------------------------------------------------------

// A linear colour scaled to a Rec. 709 luminance of 1, so that intensity_cd stays photometric.
struct Colour {
  double r, g, b;
};
Colour Luminous(double r, double g, double b) {
  const double luminance = 0.2126 * r + 0.7152 * g + 0.0722 * b;
  return {r / luminance, g / luminance, b / luminance};
}
// Annex 14 Appendix 1's aeronautical ground light colours, as linear RGB near their chromaticity
// areas: variable white (a filament lamp's), yellow, green, red and blue.
Colour White() { return Luminous(1.0, 0.92, 0.78); }
Colour Yellow() { return Luminous(1.0, 0.62, 0.08); }
Colour Green() { return Luminous(0.05, 1.0, 0.45); }
Colour Red() { return Luminous(1.0, 0.04, 0.02); }
Colour Blue() { return Luminous(0.12, 0.25, 1.0); }

// --- Beams ---------------------------------------------------------------------------------------

// An Annex 14 Appendix 2 isocandela diagram: half-widths in degrees, horizontal (a) and vertical
// (b), of the main beam's ellipse, of the 50 % one and of the 10 % one.
struct Isocandela {
  double a[3], b[3];
};
constexpr Isocandela kApproachCentreBeam{{10, 14, 15}, {5.5, 6.5, 8.5}};  // Figure A2-1
constexpr Isocandela kApproachSideRowBeam{{7, 11.5, 16.5}, {5, 6, 8}};    // Figure A2-2
constexpr Isocandela kThresholdBeam{{5.5, 7.5, 9}, {4.5, 6, 8.5}};        // Figure A2-3
constexpr Isocandela kTouchdownZoneBeam{{5, 7, 8.5}, {3.5, 6, 8.5}};      // Figure A2-5
constexpr Isocandela kRunwayCentreBeam{{5, 7, 8.5}, {4.5, 8.5, 10}};      // Figures A2-6, 7
constexpr Isocandela kRunwayEndBeam{{6, 7.5, 9}, {2.25, 5, 6.5}};         // Figure A2-8
constexpr Isocandela kRunwayEdgeBeam45{{5.5, 7.5, 9}, {3.5, 6, 8.5}};     // Figure A2-9
constexpr Isocandela kRunwayEdgeBeam60{{6.5, 8.5, 10}, {3.5, 6, 8.5}};    // Figure A2-10

// The engine's lobe standing for a diagram (the header's rule) and its peak per main-beam average.
struct LobeFit {
  double horizontal_deg, vertical_deg, peak_per_average;
};
LobeFit FitLobe(const Isocandela& d) {
  // The lobe gives I (1 - r^2): 50 % of the peak where r^2 = 1/2, 10 % where r^2 = 0.9.
  auto half_width = [](double at_half, double at_tenth) {
    return std::atan(std::max(std::sqrt(2.0) * std::tan(Radians(at_half)),
                              std::tan(Radians(at_tenth)) / std::sqrt(0.9)));
  };
  const double h = half_width(d.a[1], d.a[2]), v = half_width(d.b[1], d.b[2]);
  // The mean of x^2 over an ellipse of half-axis a is a^2 / 4: the mean of 1 - r^2 over the main
  // beam follows.
  const double ta = std::tan(Radians(d.a[0])) / std::tan(h);
  const double tb = std::tan(Radians(d.b[0])) / std::tan(v);
  return {Degrees(h), Degrees(v), 1 / (1 - (ta * ta + tb * tb) / 4)};
}

void SetVec(v1::Vec3* out, const Vec3& v) {
  out->set_x(v.x);
  out->set_y(v.y);
  out->set_z(v.z);
}

// A light of `group` and `colour`, `cd` candela, omnidirectional.
v1::LightPoint OmniLight(const char* group, const Colour& colour, double cd,
                         double radius_m = 0.1) {
  v1::LightPoint p;
  p.mutable_color()->set_r(static_cast<float>(colour.r));
  p.mutable_color()->set_g(static_cast<float>(colour.g));
  p.mutable_color()->set_b(static_cast<float>(colour.b));
  p.set_intensity_cd(cd);
  p.set_group(group);
  p.set_radius_m(radius_m);
  return p;
}

// A directional light: peak `peak_cd` along `axis`, the given half-widths and back fraction.
v1::LightPoint LobeLight(const char* group, const Colour& colour, double peak_cd, const Vec3& axis,
                         double horizontal_deg, double vertical_deg, double back_fraction = 0,
                         double radius_m = 0.1) {
  v1::LightPoint p = OmniLight(group, colour, peak_cd, radius_m);
  v1::LightLobe* lobe = p.mutable_lobe();
  SetVec(lobe->mutable_axis(), Normalize(axis));
  lobe->set_horizontal_deg(horizontal_deg);
  lobe->set_vertical_deg(vertical_deg);
  lobe->set_back_fraction(back_fraction);
  return p;
}

// A light whose beam follows an Annex 14 isocandela diagram, its main beam averaging
// `average_cd`; `omni_cd` of it shows every way (an elevated edge light seen from the side).
v1::LightPoint AnnexLight(const char* group, const Colour& colour, double average_cd,
                          const Isocandela& diagram, const Vec3& axis, double omni_cd = 0) {
  const LobeFit fit = FitLobe(diagram);
  const double peak = average_cd * fit.peak_per_average;
  return LobeLight(group, colour, peak, axis, fit.horizontal_deg, fit.vertical_deg, omni_cd / peak);
}

void AddPoint(v1::Scene* scene, const Vec3& at, v1::LightPoint light) {
  SetVec(light.mutable_position(), at);
  *scene->add_lights() = std::move(light);
}

// `count` lights equally spaced from `start` to `end` (both included; one light: at `start`).
void AddRow(v1::Scene* scene, const Vec3& start, const Vec3& end, int count,
            const v1::LightPoint& light, double sequence_s = 0) {
  if (count <= 0) return;
  v1::LightRow* row = scene->add_light_rows();
  SetVec(row->mutable_start(), start);
  SetVec(row->mutable_end(), count > 1 ? end : start);
  row->set_count(static_cast<uint32_t>(count));
  *row->mutable_light() = light;
  row->mutable_light()->clear_position();
  row->set_sequence_s(sequence_s);
}

// --- Runway frame --------------------------------------------------------------------------------

// Distances along the runway from its landing threshold (negative: out on the approach), lateral
// offsets to the landing pilot's right, heights above the threshold.
struct RunwayFrame {
  Vec3 origin, along, right;

  explicit RunwayFrame(const RunwayDescription& r)
      : origin(r.threshold),
        along{-std::sin(Radians(r.heading_deg)), 0, -std::cos(Radians(r.heading_deg))},
        right{std::cos(Radians(r.heading_deg)), 0, -std::sin(Radians(r.heading_deg))} {}

  Vec3 At(double s, double lateral, double height) const {
    return origin + along * s + right * lateral + kUp * height;
  }
  // A beam's axis: horizontally back down the approach (`towards_approach`) or along the landing
  // direction, turned by `toe_in_deg` towards the centre line for a light at `lateral`, raised by
  // `elevation_deg`.
  Vec3 Beam(bool towards_approach, double lateral, double toe_in_deg, double elevation_deg) const {
    const double t = Radians(toe_in_deg), e = Radians(elevation_deg);
    const double inwards = lateral > 0 ? -1 : lateral < 0 ? 1 : 0;
    const Vec3 level =
        along * ((towards_approach ? -1 : 1) * std::cos(t)) + right * (inwards * std::sin(t));
    return level * std::cos(e) + kUp * std::sin(e);
  }
};

// Heights of the fittings: elevated runway and taxiway lights stand at most 0.36 m, inset ones in
// the surface, approach lights on short masts over flat ground.
constexpr double kElevatedM = 0.35, kInsetM = 0.03, kApproachMastM = 1.0;

bool IsInstrument(RunwayCategory c) { return c != RunwayCategory::kNonInstrument; }
bool IsPrecision(RunwayCategory c) {
  return c == RunwayCategory::kPrecisionCatI || c == RunwayCategory::kPrecisionCatII ||
         c == RunwayCategory::kPrecisionCatIII;
}
bool IsCatIIOrIII(RunwayCategory c) {
  return c == RunwayCategory::kPrecisionCatII || c == RunwayCategory::kPrecisionCatIII;
}

// --- Runway systems ------------------------------------------------------------------------------

// Annex 14 5.3.9: two rows along the full length, at most 3 m outside the edges, uniformly spaced
// at most 60 m apart on an instrument runway (100 m otherwise); white, yellow over the last 600 m
// or third of the length, whichever is less, on an instrument runway. Main beam average 10,000 cd
// (Appendix 2, Figures A2-9 and A2-10; yellow: 0.4 of it), toed in 3.5 or 4.5 degrees; 50 cd
// every way besides, as an elevated light that guides circling shows at all azimuths (5.3.9.8).
void AddEdgeLights(const RunwayDescription& r, const RunwayFrame& f, v1::Scene* scene) {
  const bool wide = r.width_m >= 60;
  const Isocandela& beam = wide ? kRunwayEdgeBeam60 : kRunwayEdgeBeam45;
  const double toe_in = wide ? 4.5 : 3.5;
  const double max_spacing = IsInstrument(r.category) ? 60 : 100;
  const int intervals = static_cast<int>(std::ceil(r.length_m / max_spacing - 1e-9));
  const double spacing = r.length_m / intervals;
  const double caution = IsInstrument(r.category) ? std::min(600.0, r.length_m / 3) : 0;
  // The first light within `caution` of the far end.
  const int first_yellow =
      caution > 0 ? static_cast<int>(std::ceil((r.length_m - caution) / spacing - 1e-9))
                  : intervals + 1;
  for (double lateral : {-(r.width_m / 2 + 1), r.width_m / 2 + 1}) {
    const Vec3 axis = f.Beam(true, lateral, toe_in, beam.b[0]);
    const v1::LightPoint white = AnnexLight(kRunwayEdgeGroup, White(), 10000, beam, axis, 50);
    const v1::LightPoint yellow = AnnexLight(kRunwayEdgeGroup, Yellow(), 4000, beam, axis, 20);
    auto at = [&](int k) { return f.At(k * spacing, lateral, kElevatedM); };
    AddRow(scene, at(0), at(first_yellow - 1), std::min(first_yellow, intervals + 1), white);
    if (first_yellow <= intervals)
      AddRow(scene, at(first_yellow), at(intervals), intervals + 1 - first_yellow, yellow);
  }
}

// Lights across the runway at distance `s`, `count` of them uniformly from one edge to the other.
template <typename MakeLight>
void AddAcross(const RunwayFrame& f, double s, double width, int count, double height,
               MakeLight make, v1::Scene* scene) {
  for (int k = 0; k < count; ++k) {
    const double lateral = count > 1 ? -width / 2 + width * k / (count - 1) : 0;
    AddPoint(scene, f.At(s, lateral, height), make(lateral));
  }
}

// Annex 14 5.3.10: a row at right angles to the runway at most 3 m outside the threshold; on a
// precision approach runway uniformly spaced between the edge rows at most 3 m apart, else at
// least six. Fixed green towards the approach, 10,000 cd main beam (Figure A2-3, toe-in 3.5).
void AddThresholdLights(const RunwayDescription& r, const RunwayFrame& f, v1::Scene* scene) {
  const int count =
      IsPrecision(r.category) ? static_cast<int>(std::ceil(r.width_m / 3 - 1e-9)) + 1 : 6;
  AddAcross(
      f, -1, r.width_m, count, kInsetM,
      [&](double lateral) {
        return AnnexLight(kRunwayThresholdGroup, Green(), 10000, kThresholdBeam,
                          f.Beam(true, lateral, 3.5, kThresholdBeam.b[0]));
      },
      scene);
}

// Annex 14 5.3.11: a row at right angles to the runway at most 3 m outside its end, at least six
// lights, at most 6 m apart on a category III runway; fixed red in the direction of the runway
// (back towards the landing aircraft, dark beyond the end), 2,500 cd main beam (Figure A2-8).
void AddEndLights(const RunwayDescription& r, const RunwayFrame& f, v1::Scene* scene) {
  const int count = r.category == RunwayCategory::kPrecisionCatIII
                        ? std::max(6, static_cast<int>(std::ceil(r.width_m / 6 - 1e-9)) + 1)
                        : 6;
  AddAcross(
      f, r.length_m + 1, r.width_m, count, kInsetM,
      [&](double) {
        return AnnexLight(kRunwayEndGroup, Red(), 2500, kRunwayEndBeam,
                          f.Beam(true, 0, 0, kRunwayEndBeam.b[0]));
      },
      scene);
}

// Annex 14 5.3.12, on precision approach runways: from the threshold to the end about 15 m apart
// (30 m on category I); variable white to 900 m from the end, then alternately red and white to
// 300 m from the end, then red (the alternation from the midpoint on a runway under 1,800 m).
// 5,000 cd main beam (Figures A2-6 and A2-7; red: 0.15 of it).
void AddCentreLineLights(const RunwayDescription& r, const RunwayFrame& f, v1::Scene* scene) {
  if (!IsPrecision(r.category)) return;
  const double spacing = IsCatIIOrIII(r.category) ? 15 : 30;
  const int last = static_cast<int>(std::ceil(r.length_m / spacing - 1e-9)) - 1;
  const double coded = r.length_m < 1800 ? r.length_m / 2 : 900;
  const Vec3 axis = f.Beam(true, 0, 0, kRunwayCentreBeam.b[0]);
  const v1::LightPoint white =
      AnnexLight(kRunwayCentreGroup, White(), 5000, kRunwayCentreBeam, axis);
  const v1::LightPoint red = AnnexLight(kRunwayCentreGroup, Red(), 750, kRunwayCentreBeam, axis);
  auto at = [&](int k) { return f.At(k * spacing, 0, kInsetM); };
  // Lights k = 1..last; the first farther than `coded` from the end, and the first within 300 m.
  auto first_within = [&](double from_end) {
    return std::max(1, static_cast<int>(std::ceil((r.length_m - from_end) / spacing - 1e-9)));
  };
  const int alternate = std::min(first_within(coded), last + 1);
  const int all_red = std::max(alternate, std::min(first_within(300), last + 1));
  AddRow(scene, at(1), at(alternate - 1), alternate - 1, white);
  // The alternation starts with red.
  const int pairs = all_red - alternate;
  AddRow(scene, at(alternate), at(alternate + 2 * ((pairs + 1) / 2 - 1)), (pairs + 1) / 2, red);
  AddRow(scene, at(alternate + 1), at(alternate + 1 + 2 * (pairs / 2 - 1)), pairs / 2, white);
  AddRow(scene, at(all_red), at(last), last + 1 - all_red, red);
}

// Annex 14 5.3.13, on category II and III runways: pairs of barrettes from the threshold for
// 900 m (to the midpoint on a runway under 1,800 m), 30 m apart; each barrette three lights 1.5 m
// apart, the innermost lights of a pair as far apart as the touchdown zone marking (18 m). Fixed
// variable white towards the approach, 5,000 cd main beam (Figure A2-5, toe-in 4).
void AddTouchdownZoneLights(const RunwayDescription& r, const RunwayFrame& f, v1::Scene* scene) {
  if (!IsCatIIOrIII(r.category)) return;
  const double extent = std::min(900.0, r.length_m / 2);
  const int count = static_cast<int>(std::floor(extent / 30 + 1e-9));
  for (double lateral : {-12.0, -10.5, -9.0, 9.0, 10.5, 12.0}) {
    const v1::LightPoint light = AnnexLight(kTouchdownZoneGroup, White(), 5000, kTouchdownZoneBeam,
                                            f.Beam(true, lateral, 4, kTouchdownZoneBeam.b[0]));
    AddRow(scene, f.At(30, lateral, kInsetM), f.At(30.0 * count, lateral, kInsetM), count, light);
  }
}

// The elevation of an approach centre line light's beam at `distance` m from the threshold: the
// middle of the main beam's vertical coverage of Figure A2-1's note (0-11 degrees to 315 m,
// 0.5-11.5 to 475 m, 1.5-12.5 to 640 m, 2.5-13.5 beyond).
double ApproachCentreElevation(double distance) {
  return distance <= 315 ? 5.5 : distance <= 475 ? 6.0 : distance <= 640 ? 7.0 : 8.0;
}
// Figure A2-2's for the side rows: 0.5-10.5 to 115 m, 1-11 to 215 m, 1.5-11.5 beyond.
double ApproachSideRowElevation(double distance) {
  return distance <= 115 ? 5.5 : distance <= 215 ? 6.0 : 6.5;
}

// A crossbar `distance` m out on the approach, lights 1.5 m apart from `inner` to `outer` m each
// side of the centre line (Annex 14 5.3.4: a linear effect, gaps beside the centre line at most
// 6 m); toed in 2 degrees beyond 22.5 m.
void AddCrossbar(const RunwayFrame& f, double distance, double inner, double outer,
                 v1::Scene* scene) {
  const int count = static_cast<int>(std::floor((outer - inner) / 1.5 + 1e-9)) + 1;
  for (double side : {-1.0, 1.0}) {
    for (int k = 0; k < count; ++k) {
      const double lateral = side * (inner + 1.5 * k);
      const Vec3 axis = f.Beam(true, lateral, std::abs(lateral) > 22.5 ? 2 : 0,
                               ApproachCentreElevation(distance));
      AddPoint(scene, f.At(-distance, lateral, kApproachMastM),
               AnnexLight(kApproachGroup, White(), 20000, kApproachCentreBeam, axis));
    }
  }
}

// Annex 14 5.3.4. Precision approach (category I: 5.3.4.10-21; II and III: 5.3.4.22-39): a centre
// line of barrettes 30 m apart from 30 m to 900 m out, each five lights over 4 m, and a crossbar
// 30 m long 300 m out; on categories II and III also red side row barrettes to 270 m (three lights
// 1.5 m apart, their inner lights 18 m apart) and a crossbar 150 m out between the centre line
// and the side rows. Each centre line barrette (beyond 300 m on categories II and III) has a
// capacitor discharge light flashing twice a second in sequence from the outermost towards the
// threshold. Non-precision: the simple system, single lights 60 m apart to 420 m and the 300 m
// crossbar. Main beams 20,000 cd white (Figure A2-1), side rows 5,000 cd red (Figure A2-2).
void AddApproachLights(const RunwayDescription& r, const RunwayFrame& f, v1::Scene* scene) {
  if (!IsInstrument(r.category)) return;
  if (!IsPrecision(r.category)) {
    const v1::LightPoint light = AnnexLight(kApproachGroup, White(), 20000, kApproachCentreBeam,
                                            f.Beam(true, 0, 0, ApproachCentreElevation(300)));
    AddRow(scene, f.At(-60, 0, kApproachMastM), f.At(-420, 0, kApproachMastM), 7, light);
    AddCrossbar(f, 300, 1.5, 15, scene);
    return;
  }
  // Centre line barrettes, by the bands of elevation setting (their stations are 30 m apart).
  const struct {
    int first, last;  // stations, in 30 m
  } bands[] = {{1, 10}, {11, 15}, {16, 21}, {22, 30}};
  for (const auto& band : bands) {
    const double elevation = ApproachCentreElevation(30.0 * band.first);
    for (double lateral : {-2.0, -1.0, 0.0, 1.0, 2.0}) {
      const v1::LightPoint light = AnnexLight(kApproachGroup, White(), 20000, kApproachCentreBeam,
                                              f.Beam(true, lateral, 0, elevation));
      AddRow(scene, f.At(-30.0 * band.first, lateral, kApproachMastM),
             f.At(-30.0 * band.last, lateral, kApproachMastM), band.last - band.first + 1, light);
    }
  }
  AddCrossbar(f, 300, 4, 15, scene);
  const bool cat_ii_iii = IsCatIIOrIII(r.category);
  if (cat_ii_iii) {
    AddCrossbar(f, 150, 4, 7, scene);
    for (double lateral : {-12.0, -10.5, -9.0, 9.0, 10.5, 12.0}) {
      for (int k = 1; k <= 9; ++k) {
        const Vec3 axis = f.Beam(true, lateral, 2, ApproachSideRowElevation(30.0 * k));
        AddPoint(scene, f.At(-30.0 * k, lateral, kApproachMastM),
                 AnnexLight(kApproachGroup, Red(), 5000, kApproachSideRowBeam, axis));
      }
    }
  }
  // The sequenced flashers ("the rabbit"): row from the outermost station in; at any time one of
  // them is on, the sweep repeating twice a second.
  const int first = cat_ii_iii ? 11 : 1, flashers = 30 - first + 1;
  constexpr double kPeriodS = 0.5;
  v1::LightPoint flash = AnnexLight(kApproachFlasherGroup, White(), 20000, kApproachCentreBeam,
                                    f.Beam(true, 0, 0, ApproachCentreElevation(640)));
  flash.mutable_flash()->set_period_s(kPeriodS);
  flash.mutable_flash()->set_on_s(kPeriodS / flashers);
  AddRow(scene, f.At(-900, 0, kApproachMastM + 0.3), f.At(-30.0 * first, 0, kApproachMastM + 0.3),
         flashers, flash, kPeriodS / flashers);
}

// Annex 14 5.3.5.23-40: a wing bar of four units on the left of the runway, the inner one 15 m
// from the runway's edge, 9 m apart (ICAO Doc 9157 Part 4), each showing white above its setting
// angle and red below, the transition within 3 minutes of arc; the angles the approach slope
// +30', +10', -10', -30' from the inner unit out (2°30', 2°50', 3°10', 3°30' for 3 degrees).
//
// Each unit is two light points at one place: a white one whose lobe's lower edge lies 1.5' below
// the unit's angle and a red one whose lobe's upper edge lies 1.5' above it, so above and below
// that 3' band each unit shows one colour only. The engine's lobe falls off as 1 - r^2 towards
// its edge, by about 4 delta / sin(2 V) at delta radians inside it: so that a unit is already
// bright 0.2 degrees from its transition, both lobes are almost hemispheres (half-widths
// kPapiHalfWidthDeg, 74 % of the peak 0.2 degrees in), their axes tilted so that their edges pass
// through the transition. That also makes a unit show at every azimuth in front of it, where
// Annex 14's units show some 10 degrees either side. White 15,000 cd, red 5,000 cd (Figure A2-23
// puts white at 2 to 6.5 times red).
constexpr double kPapiHalfWidthDeg = 89.8;
constexpr double kPapiHalfTransitionDeg = 1.5 / 60;

// The four units' setting angles, inner unit first.
std::vector<double> PapiAngles(double slope_deg) {
  return {slope_deg + 0.5, slope_deg + 1.0 / 6, slope_deg - 1.0 / 6, slope_deg - 0.5};
}

void AddPapi(const RunwayDescription& r, const RunwayFrame& f, v1::Scene* scene) {
  const std::vector<double> angles = PapiAngles(r.approach_slope_deg);
  for (int k = 0; k < 4; ++k) {
    const Vec3 at = f.At(r.papi_distance_m, -(r.width_m / 2 + 15 + 9.0 * k), 0.4);
    // Elevations of the two lobes' axes, towards the approach (past 90: tilted back over the
    // unit).
    const double white_axis = angles[k] - kPapiHalfTransitionDeg + kPapiHalfWidthDeg;
    const double red_axis = angles[k] + kPapiHalfTransitionDeg - kPapiHalfWidthDeg;
    AddPoint(scene, at,
             LobeLight(kPapiGroup, White(), 15000, f.Beam(true, 0, 0, white_axis),
                       kPapiHalfWidthDeg, kPapiHalfWidthDeg, 0, 0.3));
    AddPoint(scene, at,
             LobeLight(kPapiGroup, Red(), 5000, f.Beam(true, 0, 0, red_axis), kPapiHalfWidthDeg,
                       kPapiHalfWidthDeg, 0, 0.3));
  }
}

absl::Status InvalidRunway(const RunwayDescription& r, const std::string& field,
                           const std::string& what) {
  return absl::InvalidArgumentError(
      absl::StrCat("runway '", r.designator, "' ", field, ": ", what));
}

// 01..36, then L, C or R.
bool IsDesignator(const std::string& d) {
  if (d.size() != 2 && d.size() != 3) return false;
  if (d[0] < '0' || d[0] > '3' || d[1] < '0' || d[1] > '9') return false;
  const int number = (d[0] - '0') * 10 + (d[1] - '0');
  if (number < 1 || number > 36) return false;
  return d.size() == 2 || d[2] == 'L' || d[2] == 'C' || d[2] == 'R';
}

absl::Status ValidateRunway(const RunwayDescription& r) {
  if (!IsDesignator(r.designator))
    return InvalidRunway(r, "designator",
                         "is not a runway designator (01 to 36, then L, C or R, as \"36L\")");
  if (!IsFinite(r.threshold)) return InvalidRunway(r, "threshold", "coordinate is NaN or infinite");
  if (!std::isfinite(r.heading_deg))
    return InvalidRunway(r, "heading_deg", absl::StrCat("must be finite, is ", r.heading_deg));
  constexpr double kMaxLengthM = 10000, kMaxWidthM = 150;
  if (!(r.length_m > 0 && r.length_m <= kMaxLengthM))
    return InvalidRunway(
        r, "length_m",
        absl::StrCat("must be > 0 and at most ", kMaxLengthM, " m, is ", r.length_m));
  if (!(r.width_m > 0 && r.width_m <= kMaxWidthM))
    return InvalidRunway(
        r, "width_m", absl::StrCat("must be > 0 and at most ", kMaxWidthM, " m, is ", r.width_m));
  if (r.category < RunwayCategory::kNonInstrument || r.category > RunwayCategory::kPrecisionCatIII)
    return InvalidRunway(r, "category",
                         absl::StrCat("is not a category (", static_cast<int>(r.category), ")"));
  if (!(r.approach_slope_deg >= 1 && r.approach_slope_deg <= 8))
    return InvalidRunway(r, "approach_slope_deg",
                         absl::StrCat("must be 1 to 8 degrees, is ", r.approach_slope_deg));
  if (!(r.intensity_scale > 0 && r.intensity_scale <= 1))
    return InvalidRunway(r, "intensity_scale",
                         absl::StrCat("must be > 0 and at most 1, is ", r.intensity_scale));
  if (!(r.papi_distance_m >= 0 && r.papi_distance_m < r.length_m))
    return InvalidRunway(
        r, "papi_distance_m",
        absl::StrCat("must be from 0 to the length (", r.length_m, " m), is ", r.papi_distance_m));
  return absl::OkStatus();
}

// --- Taxiways ------------------------------------------------------------------------------------

absl::Status InvalidTaxiway(const TaxiwayDescription& t, const std::string& field,
                            const std::string& what) {
  return absl::InvalidArgumentError(absl::StrCat("taxiway '", t.name, "' ", field, ": ", what));
}

absl::Status ValidateTaxiway(const TaxiwayDescription& t) {
  if (t.centre_line.size() < 2)
    return InvalidTaxiway(t, "centre_line",
                          absl::StrCat("needs at least 2 points, has ", t.centre_line.size()));
  for (size_t i = 0; i < t.centre_line.size(); ++i) {
    const std::string where = absl::StrCat("centre_line[", i, "]");
    if (!IsFinite(t.centre_line[i]))
      return InvalidTaxiway(t, where, "coordinate is NaN or infinite");
    if (i > 0 && !(Length(t.centre_line[i] - t.centre_line[i - 1]) > 0.01))
      return InvalidTaxiway(t, where, "repeats the point before it");
  }
  if (!(t.width_m > 0 && t.width_m <= 100))
    return InvalidTaxiway(t, "width_m",
                          absl::StrCat("must be > 0 and at most 100 m, is ", t.width_m));
  if (!(t.centre_spacing_m >= 3 && t.centre_spacing_m <= 60))
    return InvalidTaxiway(t, "centre_spacing_m",
                          absl::StrCat("must be 3 to 60 m, is ", t.centre_spacing_m));
  double length = 0;
  for (size_t i = 1; i < t.centre_line.size(); ++i)
    length += Length(t.centre_line[i] - t.centre_line[i - 1]);
  for (size_t i = 0; i < t.stop_bars_m.size(); ++i)
    if (!(t.stop_bars_m[i] >= 0 && t.stop_bars_m[i] <= length))
      return InvalidTaxiway(t, absl::StrCat("stop_bars_m[", i, "]"),
                            absl::StrCat("must be along the centre line (0 to ", length, " m), is ",
                                         t.stop_bars_m[i]));
  return absl::OkStatus();
}

// The horizontal direction of a polyline's segment i.
Vec3 SegmentDirection(const std::vector<Vec3>& line, size_t i) {
  return Normalize(line[i + 1] - line[i]);
}

// Whether the polyline turns by more than 10 degrees at vertex i (never at its ends).
bool TurnsAt(const std::vector<Vec3>& line, size_t i) {
  if (i == 0 || i + 1 >= line.size()) return false;
  return Dot(SegmentDirection(line, i - 1), SegmentDirection(line, i)) < std::cos(Radians(10));
}

// The polyline moved `offset` m to its right (the right of travel along it), corners mitred.
std::vector<Vec3> OffsetLine(const std::vector<Vec3>& line, double offset) {
  std::vector<Vec3> out(line.size());
  auto right_of = [](const Vec3& d) { return Normalize(Cross(d, kUp)); };
  for (size_t i = 0; i < line.size(); ++i) {
    Vec3 n;
    if (i == 0) {
      n = right_of(SegmentDirection(line, 0));
    } else if (i + 1 == line.size()) {
      n = right_of(SegmentDirection(line, i - 1));
    } else {
      const Vec3 a = right_of(SegmentDirection(line, i - 1)),
                 b = right_of(SegmentDirection(line, i));
      const Vec3 bisector = Normalize(a + b);
      n = bisector * (1 / std::max(0.5, Dot(bisector, a)));
    }
    out[i] = line[i] + n * offset;
  }
  return out;
}

// Lights along a polyline, at most `spacing` apart (half of it on segments that meet a turn),
// each segment a row from its start; the polyline's last point gets one too. `make` gives a
// segment's light from its direction.
template <typename MakeLight>
void AddAlongLine(const std::vector<Vec3>& line, const std::vector<Vec3>& turns_of, double spacing,
                  double height, MakeLight make, v1::Scene* scene) {
  for (size_t i = 0; i + 1 < line.size(); ++i) {
    const bool curved = TurnsAt(turns_of, i) || TurnsAt(turns_of, i + 1);
    const Vec3 a = line[i] + kUp * height, b = line[i + 1] + kUp * height;
    const double length = Length(b - a);
    const int intervals =
        std::max(1, static_cast<int>(std::ceil(length / (curved ? spacing / 2 : spacing) - 1e-9)));
    const bool last = i + 2 == line.size();
    const int count = last ? intervals + 1 : intervals;
    const Vec3 end = a + (b - a) * (static_cast<double>(count - 1) / intervals);
    for (const v1::LightPoint& light : make(Normalize(b - a))) AddRow(scene, a, end, count, light);
  }
}

// The point and unit direction `s` m along a polyline.
void PointAlong(const std::vector<Vec3>& line, double s, Vec3* at, Vec3* direction) {
  for (size_t i = 0; i + 1 < line.size(); ++i) {
    const double length = Length(line[i + 1] - line[i]);
    if (s <= length || i + 2 == line.size()) {
      *direction = SegmentDirection(line, i);
      *at = line[i] + *direction * std::min(s, length);
      return;
    }
    s -= length;
  }
}

}  // namespace

absl::Status ValidateRunwayDescription(const RunwayDescription& runway) {
  return ValidateRunway(runway);
}

absl::Status AddRunwayLights(const RunwayDescription& runway, v1::Scene* scene) {
  if (absl::Status valid = ValidateRunway(runway); !valid.ok()) return valid;
  const RunwayFrame frame(runway);
  const int first_light = scene->lights_size(), first_row = scene->light_rows_size();
  AddApproachLights(runway, frame, scene);
  AddThresholdLights(runway, frame, scene);
  AddEdgeLights(runway, frame, scene);
  AddCentreLineLights(runway, frame, scene);
  AddTouchdownZoneLights(runway, frame, scene);
  AddEndLights(runway, frame, scene);
  AddPapi(runway, frame, scene);
  // The selected brightness step dims every system alike.
  for (int i = first_light; i < scene->lights_size(); ++i) {
    v1::LightPoint& light = *scene->mutable_lights(i);
    light.set_intensity_cd(light.intensity_cd() * runway.intensity_scale);
  }
  for (int i = first_row; i < scene->light_rows_size(); ++i) {
    v1::LightPoint& light = *scene->mutable_light_rows(i)->mutable_light();
    light.set_intensity_cd(light.intensity_cd() * runway.intensity_scale);
  }
  return absl::OkStatus();
}

// Annex 14 5.3.17 (centre line): fixed green, on straight sections at most 30 m apart (15 m for
// runway visual ranges under 350 m), closer on curves; each fitting shows both ways along the
// taxiway, modelled as two lights of 100 cd with 40 x 20 degree lobes (broader than Appendix 2's
// taxiway beams, so that the pattern shows from the approach). 5.3.18 (edge): fixed blue, at most
// 3 m outside the edges, at most 60 m apart on straight sections, closer on curves, showing at
// all azimuths and up to 75 degrees (at least 2 cd to 6 degrees): 10 cd every way. 5.3.20 (stop
// bars): across the taxiway at the holding position, at most 3 m apart, fixed red towards the
// approaching traffic, with an elevated light at each end: 200 cd in a 20 x 10 degree lobe.
absl::Status AddTaxiwayLights(const TaxiwayDescription& taxiway, v1::Scene* scene) {
  if (absl::Status valid = ValidateTaxiway(taxiway); !valid.ok()) return valid;
  const std::vector<Vec3>& line = taxiway.centre_line;
  AddAlongLine(
      line, line, taxiway.centre_spacing_m, kInsetM,
      [](const Vec3& d) {
        std::vector<v1::LightPoint> both;
        for (double way : {1.0, -1.0}) {
          const Vec3 axis = d * (way * std::cos(Radians(5))) + kUp * std::sin(Radians(5));
          both.push_back(LobeLight(kTaxiwayCentreGroup, Green(), 100, axis, 40, 20));
        }
        return both;
      },
      scene);
  for (double side : {-1.0, 1.0}) {
    AddAlongLine(
        OffsetLine(line, side * (taxiway.width_m / 2 + 1)), line, 60, kElevatedM,
        [](const Vec3&) {
          return std::vector<v1::LightPoint>{OmniLight(kTaxiwayEdgeGroup, Blue(), 10)};
        },
        scene);
  }
  for (double s : taxiway.stop_bars_m) {
    Vec3 at, direction;
    PointAlong(line, s, &at, &direction);
    const Vec3 right = Normalize(Cross(direction, kUp));
    const Vec3 facing = direction * (-std::cos(Radians(3))) + kUp * std::sin(Radians(3));
    const v1::LightPoint light = LobeLight(kStopBarGroup, Red(), 200, facing, 20, 10);
    const int count = static_cast<int>(std::ceil(taxiway.width_m / 3 - 1e-9)) + 1;
    const Vec3 from = at - right * (taxiway.width_m / 2), to = at + right * (taxiway.width_m / 2);
    AddRow(scene, from + kUp * kInsetM, to + kUp * kInsetM, count, light);
    for (double end : {-1.0, 1.0})
      AddPoint(scene, at + right * (end * (taxiway.width_m / 2 + 1.5)) + kUp * 0.8, light);
  }
  return absl::OkStatus();
}

// Annex 14 6.2 and Table 6-3: a low-intensity type B light is fixed red of at least 32 cd; a
// medium-intensity type B light flashes red, 2,000 cd, 20 to 60 times a minute (here 30).
absl::Status AddObstacleLights(const std::vector<Vec3>& positions, double height_m,
                               v1::Scene* scene) {
  if (!(height_m > 0 && height_m < 1000))
    return absl::InvalidArgumentError(
        absl::StrCat("obstacle lights: height_m must be > 0 and under 1000 m, is ", height_m));
  for (size_t i = 0; i < positions.size(); ++i)
    if (!IsFinite(positions[i]))
      return absl::InvalidArgumentError(
          absl::StrCat("obstacle lights: positions[", i, "]: coordinate is NaN or infinite"));
  const bool medium = height_m >= 45;
  v1::LightPoint light = OmniLight(kObstacleGroup, Red(), medium ? 2000 : 32);
  if (medium) {
    light.mutable_flash()->set_period_s(2);
    light.mutable_flash()->set_on_s(0.3);
  }
  for (const Vec3& at : positions) AddPoint(scene, at, light);
  return absl::OkStatus();
}

}  // namespace aperture
