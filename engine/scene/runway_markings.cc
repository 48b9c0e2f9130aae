#include "scene/runway_markings.h"

#include <algorithm>
#include <cmath>

#include "absl/strings/str_cat.h"
#include "texture/packed/apv_file.h"
#include "texture/packed/rgba8_image.h"

namespace aperture {
namespace {

// --- Annex 14, Volume I, 5.2 (docs/SCENE.md, "Runway markings") ---------------------------------

// 5.2.4.4, 5.2.4.5: the threshold stripes begin 6 m from the threshold and are at least 30 m long.
constexpr double kStripeStartM = 6, kStripeLengthM = 30;
// 5.2.4.6: the stripes reach to within 3 m of the runway's edges or to 27 m from the centre line,
// whichever is less.
constexpr double kStripeEdgeClearanceM = 3, kStripeMaxReachM = 27;
// Figure 5-2: the designation marking 12 m beyond the threshold stripes; the centre line begins
// 12 m beyond the designation marking.
constexpr double kDesignationGapM = 12, kCentreLineGapM = 12;
// Figure 5-3: characters 9 m tall and 3 m wide. Our spacing: 3 m between the two digits, 6 m
// between the letter (nearer the threshold) and the number.
constexpr double kGlyphHeightM = 9, kGlyphWidthM = 3, kDigitGapM = 3, kLetterGapM = 6;
// 5.2.3.4: stripes of 30 m with gaps of 20 m (a stripe and a gap at least 50 m, at most 75 m).
constexpr double kCentreStripeM = 30, kCentreGapM = 20;
// 5.2.6.5, Figure 5-6 (B): each marking of a touchdown zone pair is one to three stripes 22.5 m
// long, 1.8 m wide, 1.5 m apart; pairs every 150 m from the threshold; a pair within 50 m of the
// aiming point is left out.
constexpr double kTdzLengthM = 22.5, kTdzStripeM = 1.8, kTdzStripeGapM = 1.5, kTdzSpacingM = 150,
                 kTdzAimingClearanceM = 50;
constexpr int kTdzStripes[6] = {3, 3, 2, 2, 1, 1};

// Table 5-1: the aiming point's place and size by landing distance available (LDA); where the
// table gives a range we take the values named.
struct AimingPoint {
  double start_m, length_m, width_m, inner_spacing_m;
};
AimingPoint AimingPointFor(double lda_m) {
  if (lda_m < 800) return {150, 30, 4, 6};
  if (lda_m < 1200) return {250, 30, 6, 9};
  if (lda_m < 2400) return {300, 45, 9, 18};  // 45-60 m long, 6-10 m wide, 18-22.5 m apart
  return {400, 45, 9, 18};
}

// 5.2.6.3: pairs of touchdown zone markings by LDA.
int TouchdownPairsFor(double lda_m) {
  if (lda_m < 900) return 1;
  if (lda_m < 1200) return 2;
  if (lda_m < 1500) return 3;
  if (lda_m < 2400) return 4;
  return 6;
}

// 5.2.4.6: stripes by runway width (18, 23, 30, 45, 60 m: 4, 6, 8, 12, 16).
int ThresholdStripesFor(double width_m) {
  if (width_m >= 60) return 16;
  if (width_m >= 45) return 12;
  if (width_m >= 30) return 8;
  if (width_m >= 23) return 6;
  return 4;
}

// 5.2.3.5: 0.9 m on category II and III runways, 0.45 m on category I and non-precision runways
// (code 3 or 4), 0.3 m otherwise.
double CentreLineWidthFor(RunwayCategory c) {
  switch (c) {
    case RunwayCategory::kPrecisionCatII:
    case RunwayCategory::kPrecisionCatIII:
      return 0.9;
    case RunwayCategory::kPrecisionCatI:
    case RunwayCategory::kNonPrecision:
      return 0.45;
    case RunwayCategory::kNonInstrument:
      break;
  }
  return 0.3;
}

// 5.2.7.4: side stripes 0.9 m wide on runways 30 m wide or more, 0.45 m on narrower ones.
double SideStripeWidthFor(double width_m) { return width_m >= 30 ? 0.9 : 0.45; }

constexpr double kMinWidthM = 18;  // the threshold table's narrowest runway

// --- The designation font ------------------------------------------------------------------------

// A bar of a glyph on a grid of 0.75 m cells, 4 across and 12 along (3 m x 9 m): columns from the
// glyph's left as the landing pilot reads it, rows from its top (the end farther from the
// threshold). Vertical strokes are one column wide, horizontal bars two rows: the proportions of
// Figure 5-3 (strokes about 0.74 m, bars about 1.5 m).
struct Bar {
  double c0, c1;
  int r0, r1;
};
constexpr double kCellM = 0.75;
constexpr Bar kTop{0, 4, 0, 2}, kMiddle{0, 4, 5, 7}, kBottom{0, 4, 10, 12};
constexpr Bar kUpperLeft{0, 1, 0, 7}, kLowerLeft{0, 1, 5, 12};
constexpr Bar kUpperRight{3, 4, 0, 7}, kLowerRight{3, 4, 5, 12};

std::vector<Bar> Glyph(char c) {
  switch (c) {
    case '0':
      return {kTop, kBottom, kUpperLeft, kLowerLeft, kUpperRight, kLowerRight};
    case '1':
      return {{1.4, 2.4, 0, 12}, {0.4, 1.4, 0, 2}};
    case '2':
      return {kTop, kUpperRight, kMiddle, kLowerLeft, kBottom};
    case '3':
      return {kTop, kUpperRight, kMiddle, kLowerRight, kBottom};
    case '4':
      return {kUpperLeft, kMiddle, kUpperRight, kLowerRight};
    case '5':
      return {kTop, kUpperLeft, kMiddle, kLowerRight, kBottom};
    case '6':
      return {kTop, kUpperLeft, kLowerLeft, kMiddle, kLowerRight, kBottom};
    case '7':
      return {kTop, kUpperRight, kLowerRight};
    case '8':
      return {kTop, kMiddle, kBottom, kUpperLeft, kLowerLeft, kUpperRight, kLowerRight};
    case '9':
      return {kTop, kUpperLeft, kUpperRight, kMiddle, kLowerRight, kBottom};
    case 'L':
      return {{0, 1, 0, 12}, kBottom};
    case 'C':
      return {kTop, {0, 1, 0, 12}, kBottom};
    case 'R':  // a P with a stepped leg from the bowl to the bottom right
      return {kTop,          {0, 1, 0, 12},    kUpperRight,
              kMiddle,       {1.4, 2.4, 7, 9}, {2.2, 3.2, 9, 10},
              {3, 4, 10, 12}};
    default:
      return {};
  }
}

// --- Layout --------------------------------------------------------------------------------------

struct Layout {
  double width_m, length_m;
  double texel_x;  // width_m / texels across
  int columns, rows;
};

Layout LayoutOf(const RunwayDescription& r) {
  Layout l;
  l.width_m = r.width_m;
  l.length_m = r.length_m;
  l.columns = std::max(1, static_cast<int>(std::lround(r.width_m / kMarkingTexelAcrossM)));
  l.texel_x = r.width_m / l.columns;
  l.rows = static_cast<int>(std::ceil(r.length_m / kMarkingTexelAlongM - 1e-9));
  return l;
}

// Where the designation marking ends, from the threshold.
double DesignationEndM(const std::string& designator) {
  const double start = kStripeStartM + kStripeLengthM + kDesignationGapM;
  return start + kGlyphHeightM + (designator.size() == 3 ? kLetterGapM + kGlyphHeightM : 0);
}

// One end's markings in its own frame (x across from its left edge, y from its threshold).
void AddEndMarkings(const RunwayDescription& r, const std::string& designator,
                    std::vector<MarkingRect>& out) {
  const double w = r.width_m, centre = w / 2, lda = r.length_m;
  auto add = [&](double x0, double y0, double x1, double y1, MarkingKind kind) {
    out.push_back({x0, y0, x1, y1, kind, designator});
  };
  const double side = SideStripeWidthFor(w);
  // Aiming point and touchdown zone markings stay inside the side stripes (on runways narrower
  // than their layout, 30 m wide with a long LDA, they are cut there).
  auto add_inside = [&](double x0, double y0, double x1, double y1, MarkingKind kind) {
    x0 = std::max(x0, side), x1 = std::min(x1, w - side);
    if (x1 - x0 >= kMarkingTexelAcrossM) add(x0, y0, x1, y1, kind);
  };

  // Threshold stripes: n stripes of width s, s apart, 2 s apart across the centre line, reaching
  // n s from it.
  const int n = ThresholdStripesFor(w);
  const double reach = std::min(centre - kStripeEdgeClearanceM, kStripeMaxReachM);
  const double texel = w / std::max(1.0, std::round(w / kMarkingTexelAcrossM));
  const double s = std::floor(reach / n / texel + 1e-9) * texel;
  for (int k = 0; k < n / 2; ++k) {
    const double inner = s + 2 * k * s;
    add(centre + inner, kStripeStartM, centre + inner + s, kStripeStartM + kStripeLengthM,
        MarkingKind::kThreshold);
    add(centre - inner - s, kStripeStartM, centre - inner, kStripeStartM + kStripeLengthM,
        MarkingKind::kThreshold);
  }

  // Designation: the letter nearer the threshold, the number beyond it (read from the approach,
  // the number above the letter).
  const double first = kStripeStartM + kStripeLengthM + kDesignationGapM;
  auto add_glyph = [&](char c, double left, double bottom) {
    for (const Bar& b : Glyph(c))
      add(left + b.c0 * kCellM, bottom + kGlyphHeightM - b.r1 * kCellM, left + b.c1 * kCellM,
          bottom + kGlyphHeightM - b.r0 * kCellM, MarkingKind::kDesignation);
  };
  double number_bottom = first;
  if (designator.size() == 3) {
    add_glyph(designator[2], centre - kGlyphWidthM / 2, first);
    number_bottom = first + kGlyphHeightM + kLetterGapM;
  }
  add_glyph(designator[0], centre - kDigitGapM / 2 - kGlyphWidthM, number_bottom);
  add_glyph(designator[1], centre + kDigitGapM / 2, number_bottom);

  // Aiming point, then the touchdown zone pairs around it, on this end's half of the runway.
  const bool aiming = r.category != RunwayCategory::kNonInstrument || lda >= 1200;
  const AimingPoint a = AimingPointFor(lda);
  const double half = r.length_m / 2;
  if (aiming && a.start_m + a.length_m <= half) {
    const double inner = a.inner_spacing_m / 2;
    add_inside(centre + inner, a.start_m, centre + inner + a.width_m, a.start_m + a.length_m,
               MarkingKind::kAimingPoint);
    add_inside(centre - inner - a.width_m, a.start_m, centre - inner, a.start_m + a.length_m,
               MarkingKind::kAimingPoint);
  }
  const bool precision = r.category == RunwayCategory::kPrecisionCatI ||
                         r.category == RunwayCategory::kPrecisionCatII ||
                         r.category == RunwayCategory::kPrecisionCatIII;
  if (precision) {
    const int pairs = TouchdownPairsFor(lda);
    for (int k = 0; k < pairs; ++k) {
      const double y0 = kTdzSpacingM * (k + 1), y1 = y0 + kTdzLengthM;
      if (y1 > half) break;
      if (aiming && y0 < a.start_m + a.length_m + kTdzAimingClearanceM &&
          y1 > a.start_m - kTdzAimingClearanceM)
        continue;
      for (int i = 0; i < kTdzStripes[k]; ++i) {
        const double inner = a.inner_spacing_m / 2 + i * (kTdzStripeM + kTdzStripeGapM);
        add_inside(centre + inner, y0, centre + inner + kTdzStripeM, y1,
                   MarkingKind::kTouchdownZone);
        add_inside(centre - inner - kTdzStripeM, y0, centre - inner, y1,
                   MarkingKind::kTouchdownZone);
      }
    }
  }
}

absl::Status InvalidMarkings(const RunwayDescription& r, const std::string& field,
                             const std::string& what) {
  return absl::InvalidArgumentError(
      absl::StrCat("runway '", r.designator, "' markings: ", field, ": ", what));
}

}  // namespace

std::string ReciprocalDesignator(const std::string& designator) {
  const int number = (designator[0] - '0') * 10 + (designator[1] - '0');
  const int opposite = number > 18 ? number - 18 : number + 18;
  std::string out = absl::StrCat(opposite / 10, opposite % 10);
  if (designator.size() == 3)
    out += designator[2] == 'L' ? 'R' : designator[2] == 'R' ? 'L' : designator[2];
  return out;
}

absl::StatusOr<std::vector<MarkingRect>> RunwayMarkingRects(const RunwayDescription& runway) {
  if (absl::Status valid = ValidateRunwayDescription(runway); !valid.ok()) return valid;
  if (runway.width_m < kMinWidthM)
    return InvalidMarkings(
        runway, "width_m",
        absl::StrCat("must be at least ", kMinWidthM,
                     " m (Annex 14's narrowest threshold marking), is ", runway.width_m));
  const std::string far_end = ReciprocalDesignator(runway.designator);
  const double min_length =
      DesignationEndM(runway.designator) + DesignationEndM(far_end) + 2 * kCentreLineGapM;
  if (runway.length_m < min_length)
    return InvalidMarkings(runway, "length_m",
                           absl::StrCat("must be at least ", min_length,
                                        " m to hold both ends' markings, is ", runway.length_m));

  const Layout l = LayoutOf(runway);
  std::vector<MarkingRect> rects;
  AddEndMarkings(runway, runway.designator, rects);
  const size_t near_count = rects.size();
  AddEndMarkings(runway, far_end, rects);
  // The far end's frame turned half round: x from the other edge, y from the other end.
  for (size_t i = near_count; i < rects.size(); ++i) {
    MarkingRect& m = rects[i];
    m = {l.width_m - m.x1, l.length_m - m.y1, l.width_m - m.x0, l.length_m - m.y0, m.kind, m.end};
  }

  // The centre line between the two designation markings: whole stripe-and-gap periods, centred.
  const double line_start = DesignationEndM(runway.designator) + kCentreLineGapM;
  const double line_end = l.length_m - DesignationEndM(far_end) - kCentreLineGapM;
  const double period = kCentreStripeM + kCentreGapM;
  const int stripes = static_cast<int>(std::floor((line_end - line_start + kCentreGapM) / period));
  const double offset = (line_end - line_start - (stripes * period - kCentreGapM)) / 2;
  const double half_line = CentreLineWidthFor(runway.category) / 2;
  for (int k = 0; k < stripes; ++k) {
    const double y0 = line_start + offset + k * period;
    rects.push_back({l.width_m / 2 - half_line, y0, l.width_m / 2 + half_line, y0 + kCentreStripeM,
                     MarkingKind::kCentreLine, runway.designator});
  }
  // Side stripes along both edges, the full length.
  const double side = SideStripeWidthFor(l.width_m);
  rects.push_back({0, 0, side, l.length_m, MarkingKind::kSideStripe, runway.designator});
  rects.push_back(
      {l.width_m - side, 0, l.width_m, l.length_m, MarkingKind::kSideStripe, runway.designator});

  // Every edge onto the texture's texel edges.
  for (MarkingRect& m : rects) {
    auto snap_x = [&](double x) { return std::round(x / l.texel_x) * l.texel_x; };
    auto snap_y = [&](double y) {
      return std::round(y / kMarkingTexelAlongM) * kMarkingTexelAlongM;
    };
    m.x0 = snap_x(m.x0), m.x1 = snap_x(m.x1), m.y0 = snap_y(m.y0), m.y1 = snap_y(m.y1);
  }
  return rects;
}

absl::StatusOr<packed::PackedTexture> RunwayMarkingsTexture(const RunwayDescription& runway) {
  auto rects = RunwayMarkingRects(runway);
  if (!rects.ok()) return rects.status();
  const Layout l = LayoutOf(runway);
  packed::IndexedImage image;
  image.width = static_cast<uint32_t>(l.columns);
  image.height = static_cast<uint32_t>(l.rows);
  image.palette = {packed::PackRgba8(kAsphaltGrey, kAsphaltGrey, kAsphaltGrey, 255),
                   packed::PackRgba8(kPaintWhite, kPaintWhite, kPaintWhite, 255)};
  image.indices.assign(size_t{image.width} * image.height, 0);
  for (const MarkingRect& m : *rects) {
    const long i0 = std::clamp(std::lround(m.x0 / l.texel_x), 0L, long{l.columns});
    const long i1 = std::clamp(std::lround(m.x1 / l.texel_x), 0L, long{l.columns});
    const long j0 = std::clamp(std::lround(m.y0 / kMarkingTexelAlongM), 0L, long{l.rows});
    const long j1 = std::clamp(std::lround(m.y1 / kMarkingTexelAlongM), 0L, long{l.rows});
    for (long j = j0; j < j1; ++j)
      std::fill_n(image.indices.begin() + j * l.columns + i0, std::max(0L, i1 - i0), 1);
  }
  return packed::PackTexture(image, packed::Curve::kHilbert);
}

absl::Status AddRunwayMarkings(const RunwayDescription& runway, v1::Scene* scene) {
  auto texture = RunwayMarkingsTexture(runway);
  if (!texture.ok()) return texture.status();
  const std::string texture_id = absl::StrCat("runway-markings-", runway.designator);
  const std::string mesh_id = absl::StrCat("runway-", runway.designator);
  for (const v1::Texture& t : scene->textures())
    if (t.id() == texture_id)
      return InvalidMarkings(runway, "designator",
                             absl::StrCat("the scene already has a texture '", texture_id, "'"));

  const std::vector<uint8_t> apv = packed::EncodeApv(texture->view());
  v1::Texture* t = scene->add_textures();
  t->set_id(texture_id);
  t->set_encoded(std::string(apv.begin(), apv.end()));
  v1::Material* material = scene->add_materials();
  material->set_id(texture_id);
  material->mutable_base_color()->set_r(1);
  material->mutable_base_color()->set_g(1);
  material->mutable_base_color()->set_b(1);
  material->set_texture_id(texture_id);
  material->set_filter(v1::TEXTURE_FILTER_ANISO);  // a packed texture: its exact area integral

  // The corners: the threshold's left and right, then the far end's right and left (counter-
  // clockwise seen from above), with the texture's (u, v): u across, v along its rows.
  const Layout l = LayoutOf(runway);
  const double h = Radians(runway.heading_deg);
  const Vec3 along{-std::sin(h), 0, -std::cos(h)}, right{std::cos(h), 0, -std::sin(h)};
  const Vec3 origin = runway.threshold + Vec3{0, 0.01, 0};
  const double v_end = runway.length_m / (l.rows * kMarkingTexelAlongM);
  const double half = runway.width_m / 2, length = runway.length_m;
  v1::Mesh* mesh = scene->add_meshes();
  mesh->set_id(mesh_id);
  mesh->set_material_id(texture_id);
  v1::Polygon* p = mesh->add_polygons();
  const struct {
    Vec3 at;
    double u, v;
  } corners[4] = {{origin - right * half, 0, 0},
                  {origin + right * half, 1, 0},
                  {origin + right * half + along * length, 1, v_end},
                  {origin - right * half + along * length, 0, v_end}};
  for (const auto& c : corners) {
    v1::Vec3* q = p->add_vertices();
    q->set_x(c.at.x);
    q->set_y(c.at.y);
    q->set_z(c.at.z);
    v1::Vec2* uv = p->add_uvs();
    uv->set_u(c.u);
    uv->set_v(c.v);
  }
  return absl::OkStatus();
}

}  // namespace aperture
