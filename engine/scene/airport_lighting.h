// Airport lighting generated to ICAO Annex 14, Volume I (chapter 5.3 and the isocandela diagrams
// of its Appendix 2): from a runway's or a taxiway's geometry, the LightRows and LightPoints of
// its lights, with their layout, colours, intensities and lobes, one light group per system so
// that a host can switch each system and set its brightness step (SceneUpdate.light_groups).
// docs/SCENE.md, "Airport lighting", tabulates what is generated and where each figure comes from.
//
// Colours are scaled to a Rec. 709 luminance of 1, so a light's intensity_cd is its photometric
// intensity whatever its colour. A lobe stands for an Annex 14 isocandela diagram (ellipses of the
// main beam, of 50 % and of 10 % of it, half-widths a horizontally and b vertically): it is the
// smallest of the engine's lobes (I (1 - r^2), light_points.h) that keeps at least 50 % and 10 % of
// its peak on the two outer ellipses, and its peak is set so that its average over the main beam's
// ellipse is the intensity the table gives.
#pragma once

#include <string>
#include <vector>

#include "absl/status/status.h"
#include "aperture/v1/scene.pb.h"
#include "scene/vec.h"

namespace aperture {

// The light groups (LightPoint.group) the generator fills, one per system.
inline constexpr char kRunwayEdgeGroup[] = "runway-edge";
inline constexpr char kRunwayThresholdGroup[] = "runway-threshold";
inline constexpr char kRunwayEndGroup[] = "runway-end";
inline constexpr char kRunwayCentreGroup[] = "runway-centre";
inline constexpr char kTouchdownZoneGroup[] = "touchdown-zone";
inline constexpr char kApproachGroup[] = "approach";
inline constexpr char kApproachFlasherGroup[] = "approach-flashers";
inline constexpr char kPapiGroup[] = "papi";
inline constexpr char kTaxiwayCentreGroup[] = "taxiway-centre";
inline constexpr char kTaxiwayEdgeGroup[] = "taxiway-edge";
inline constexpr char kStopBarGroup[] = "stop-bar";
inline constexpr char kObstacleGroup[] = "obstacle";

// Annex 14's runway types (chapter 1 definitions): which systems a runway gets and how dense.
enum class RunwayCategory {
  kNonInstrument,
  kNonPrecision,
  kPrecisionCatI,
  kPrecisionCatII,
  kPrecisionCatIII,
};

// One landing direction of a runway. The world is the scene's: y up, metres.
struct RunwayDescription {
  // The landing direction's designator: its magnetic heading in tens of degrees, 01 to 36, then
  // L, C or R on parallel runways ("36L").
  std::string designator;
  Vec3 threshold;          // the landing threshold's centre, on the runway's surface
  double heading_deg = 0;  // the landing direction as a yaw: 0 along -z, 90 along -x
  double length_m = 0;     // from the threshold to the runway's far end
  double width_m = 0;
  RunwayCategory category = RunwayCategory::kPrecisionCatI;
  double approach_slope_deg = 3;  // the PAPI's approach slope, 1 to 8 degrees
  double papi_distance_m = 300;   // from the threshold to the PAPI's wing bar, less than length_m
  // The brightness step the tower has selected, as a share of the full intensities below (0 to
  // 1]: a five-step system's steps are about 100, 25, 5, 1 and 0.2 %. The intensities given in
  // the scene are these (SceneUpdate.light_groups scales them further).
  double intensity_scale = 1;
};

// OK, or InvalidArgument naming the field of the first bad datum (AddRunwayLights' checks; the
// runway markings make the same).
absl::Status ValidateRunwayDescription(const RunwayDescription& runway);

// Appends the runway's lights to `scene`: edge, threshold, end, centre line and touchdown zone
// lights, the approach lighting system with its sequenced flashers, and the PAPI, as the
// category calls for them (docs/SCENE.md, "Airport lighting"). Bad data (a zero, negative or
// non-finite length or width, an unknown designator, a NaN coordinate) is InvalidArgument naming
// the field, and nothing is appended.
absl::Status AddRunwayLights(const RunwayDescription& runway, v1::Scene* scene);

// A taxiway's centre line, drawn from where traffic enters it (an apron) towards where it leaves
// (a runway), on the surface.
struct TaxiwayDescription {
  std::string name;               // names the taxiway in errors
  std::vector<Vec3> centre_line;  // at least two points, metres
  double width_m = 23;
  // The centre line lights' spacing on straight sections: 15 m where the taxiway serves runway
  // visual ranges below 350 m, else at most 30 m; half of it on curves.
  double centre_spacing_m = 15;
  // Distances along the centre line of stop bars (at runway-holding positions), showing red to
  // traffic coming from the centre line's start.
  std::vector<double> stop_bars_m;
};

// Appends the taxiway's green centre line lights, blue edge lights and red stop bars; errors name
// the taxiway and the field.
absl::Status AddTaxiwayLights(const TaxiwayDescription& taxiway, v1::Scene* scene);

// Appends obstacle lights (Annex 14 chapter 6) at the top of a structure `height_m` tall, one at
// each of `positions`: fixed red low-intensity lights (type B) below 45 m, flashing red
// medium-intensity lights (type B) from 45 m up.
absl::Status AddObstacleLights(const std::vector<Vec3>& positions, double height_m,
                               v1::Scene* scene);

}  // namespace aperture
