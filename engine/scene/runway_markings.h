// Runway markings generated to ICAO Annex 14, Volume I, chapter 5.2, from a runway's geometry
// (the RunwayDescription the lighting takes): threshold stripes, designation numbers and letters,
// centre line, aiming point, touchdown zone and side stripes at both ends, as rectangles, then as
// a seed 001 packed vector texture (white paint on dark asphalt) draped on the runway's polygon,
// so that the packed texture's exact area integrals anti-alias every edge. docs/SCENE.md, "Runway
// markings", tabulates each figure and its source.
#pragma once

#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "aperture/v1/scene.pb.h"
#include "scene/airport_lighting.h"
#include "texture/packed/packed_texture.h"

namespace aperture {

// The texture's texels: 0.15 m across the runway (every Annex 14 width is a multiple: 0.3, 0.45,
// 0.9, 1.5, 1.8 m) and 0.25 m along it (every length is: 6, 9, 12, 20, 22.5, 30, 45, 150, 400 m,
// and the designation font's 0.75 m cells), so that the markings' edges fall on texel edges.
inline constexpr double kMarkingTexelAcrossM = 0.15;
inline constexpr double kMarkingTexelAlongM = 0.25;

// The asphalt and the paint, 8-bit values taken as linear (as the airport map's runway: #383838
// and #F0F0F0).
inline constexpr uint8_t kAsphaltGrey = 0x38, kPaintWhite = 0xF0;

// What a marking rectangle belongs to.
enum class MarkingKind {
  kThreshold,
  kDesignation,
  kCentreLine,
  kAimingPoint,
  kTouchdownZone,
  kSideStripe,
};

// One painted rectangle in the runway's frame, metres: `x` across from the left edge as seen
// landing on the description's designator (0 to width), `y` along from its threshold (0 to
// length). Edges lie on the texture's texel edges.
struct MarkingRect {
  double x0, y0, x1, y1;
  MarkingKind kind;
  std::string end;  // the designator of the landing direction it serves ("36L", "18R")
};

// The opposite direction's designator: the number 18 apart, L and R exchanged ("36L" -> "18R").
// The designator must be valid.
std::string ReciprocalDesignator(const std::string& designator);

// Every marking rectangle of the runway, both ends. Bad data is InvalidArgument naming the field:
// the lighting's checks (ValidateRunwayDescription), a width under 18 m (Annex 14's narrowest
// threshold marking) or a runway too short for both ends' markings.
absl::StatusOr<std::vector<MarkingRect>> RunwayMarkingRects(const RunwayDescription& runway);

// The markings as a two-colour packed texture: `width` texels across (x, from the left edge), rows
// along (y, row 0 at the threshold), texel (i, j) paint when its centre is in a rectangle.
absl::StatusOr<packed::PackedTexture> RunwayMarkingsTexture(const RunwayDescription& runway);

// Appends to `scene` the texture "runway-markings-<designator>" (.apv bytes), its material and the
// mesh "runway-<designator>": the runway's rectangle 1 cm above the threshold's height (over a
// ground at that height, under inset lights at 3 cm), its uvs mapping the texture. A scene with
// objects must place the mesh with one. Errors as RunwayMarkingRects; nothing is appended then.
absl::Status AddRunwayMarkings(const RunwayDescription& runway, v1::Scene* scene);

}  // namespace aperture
