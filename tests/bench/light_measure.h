// What the light benchmark (light_blink_bench.cc) measures of one light point in one frame: where
// it falls and what its pixels should sum to, from the camera and docs/SCENE.md's photometry
// alone ("Light points"); its energy in Aperture's frame, isolated exactly (ApertureLightProbe);
// and the points an osgSim-based image generator draws for it (PeerLightOf).
//
// How a light's energy is isolated, exactly. Aperture draws light points after the polygons, by
// adding each footprint's filtered energy to the pixels (render/light_pass.h): a frame with the
// lights is the frame without them plus, per light, that light's own image. So the probe renders
// the light's window of the frame (RenderSettings::region, through the public RenderFrame) twice,
// once with the scene's polygons and that light alone, once with the polygons only, and sums the
// difference's Rec. 709 luminance. No neighbour's light and no surface reaches the sum, whatever
// the lights' spacing; the only error is the float rounding of the two images (about 1e-7 of the
// light's energy). The window is the footprint's box widened by the filter's reach and a margin;
// any of the light's image on the window's border is an error (it would be lost). The same
// decomposition, summed over all the lights of a frame, must give the whole frame's light, which
// the benchmark checks on its first frame (its "additivity" line).
#pragma once

#include <vector>

#include "absl/status/statusor.h"
#include "base/pixel_rect.h"
#include "light_point_peer.h"
#include "render/renderer.h"
#include "scene/camera.h"
#include "scene/scene.h"

namespace aperture {

double Luminance(const Rgba& c);
double Median(std::vector<double> v);

// A camera and a frame size, with what projecting through them needs.
struct FrameView {
  FrameView(const Camera& camera, int width, int height);

  Camera camera;
  int width, height;
  FrustumTangents t;
  double sx, sy;  // the tangent-plane extent of one pixel
  Mat3 to_camera;
};

// Whether the benchmark can hold a light to a steady analytic energy: a light that flashes blinks
// by design, and one attached to an object moves with it (the approach does not move objects,
// but its frame is the object's).
bool SteadyWorldLight(const PointLight& light);

// A light as a frame should show it (docs/SCENE.md, "Light points").
struct LightView {
  bool drawn = false;       // ahead of the near plane and sending light towards the eye
  double x = 0, y = 0;      // its projection, pixels (row 0 at the top)
  double distance = 0;      // metres
  double intensity_cd = 0;  // towards the eye: the lobe's falloff, the group's scale
  // What its pixels sum to, per unit of its colour: exposure x I / d^2 / (one pixel's solid
  // angle there), times the transmission T through the fog plus the halo's forward share of the
  // scattered rest. Its luminance is this times Luminance(colour).
  double energy = 0;
  double lamp_px = 0;       // the lamp's projected radius, pixels
  double footprint_px = 0;  // the footprint's radius (the largest of it and its halo's), pixels
  PixelRect window;         // the pixels its image may reach, with room to spare
  bool inside = false;      // the window lies inside the frame
};

// `scene` gives the light's groups, the light settings and the fog; `room_px`: the least half
// width of the window (room for the peer's points).
LightView LookAt(const Scene& scene, const PointLight& light, const FrameView& view,
                 double room_px = 0);

// A light's image in a window: its luminance summed, its centroid, and whether any of it
// reached the window's border.
struct LightImage {
  double sum = 0, x = 0, y = 0;
  bool at_border = false;
};

// `luminance`: the window's pixels row by row from the top.
LightImage ImageOf(const std::vector<double>& luminance, const PixelRect& window);

// One light in one frame through Aperture.
struct ApertureLightSample {
  LightImage image;
  bool occluded = false;  // some polygon nearer than the light hides part of its footprint
};

// Renders one light at a time over `scene`'s polygons (see the top of this file). One per thread:
// it holds its own copy of the scene, whose lights it swaps; `dark` (the scene without lights)
// is shared.
class ApertureLightProbe {
 public:
  ApertureLightProbe(const Scene& scene, const Scene& dark, const RenderSettings& settings);

  // The light's image over `window` (clipped to the frame) of the frame seen by `camera`. An
  // image reaching the window's border is an error when `whole_in_window`.
  absl::StatusOr<ApertureLightSample> Measure(const PointLight& light, const Camera& camera,
                                              const PixelRect& window, bool whole_in_window);

 private:
  Scene lit_;
  const Scene& dark_;
  RenderSettings settings_;
};

// The points osgSim draws for a light, and `nominal`: the luminance they would sum to if each
// point of size s covered exactly the disc of diameter s.
struct PeerLight {
  std::vector<PeerPoint> points;
  double nominal = 0;
};

// osgSim's points for a light: its projected lamp radius x sqrt(its intensity towards the eye),
// osgSim's intensity 1 taken as 1,000 cd, in the light's colour scaled to at most 1 (the buffers
// clamp, as an image generator's do), `min_size` pixels at least. Scaling their colour by
// (the light's energy) / nominal would give them Aperture's energy; blending is linear and a
// measured light is drawn alone, so measured / nominal is the same ratio to the analytic energy
// without that scaling, which the clamped buffers could not hold.
PeerLight PeerLightOf(const PointLight& light, const LightView& lv, const Vec3& eye,
                      double min_size);

}  // namespace aperture
