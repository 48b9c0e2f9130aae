// Light points drawn over a rendered frame (scene/light_points.h; docs/SCENE.md, "Light points").
//
// Each light's illuminance at the eye, E = I T(d) / d^2 (Allard's law: I its intensity towards the
// eye, T the fog's transmission over its distance d), becomes a pixel-value energy S = exposure x
// E / (the solid angle of one pixel at its place on the screen), spread uniformly over a small
// disc footprint (a regular octagon of the disc's area) at the light's depth. Each cell of the
// footprint is resolved by the exact cell coverage against the polygons nearer than the light
// (raster/cell_coverage.h), and integrated over the pixels' filter apertures like any polygon's
// piece. So the sum of a light's pixels is S times the visible share of its footprint, to float
// rounding, wherever it falls inside a pixel; its image's centroid follows its projection
// continuously; and a light sliding behind an edge dims continuously, by exactly the part of its
// footprint the edge covers. The polygons whose plane passes within kSurfaceOffsetM of a light
// (the runway under an edge light, the wing a navigation light sits on) do not hide it.
//
// In fog, part of the light scattered on its way forms a halo (the atmospheric point spread
// function of Narasimhan and Nayar, "Shedding Light on the Weather", CVPR 2003: its forward peak
// widens with the optical depth tau): a second, wider disc carrying I (1 - T) / d^2 x
// kHaloForwardShare, of angular radius kHaloDegPerTau x tau (at least twice the light's own).
#pragma once

#include <cstddef>

#include "absl/status/status.h"
#include "base/image.h"
#include "base/pixel_rect.h"
#include "raster/aa_filter.h"
#include "raster/projection.h"
#include "render/renderer.h"
#include "scene/camera.h"
#include "scene/scene.h"

namespace aperture {

// Polygons whose plane passes within this distance of a light do not hide it (lights stand on
// or in the surfaces they light: an elevated runway light is at most 0.36 m tall).
inline constexpr double kSurfaceOffsetM = 0.5;
// The share of the scattered light that stays near the light's direction (the halo), and the
// halo's angular radius per unit of optical depth.
inline constexpr double kHaloForwardShare = 0.5;
inline constexpr double kHaloDegPerTau = 0.25;
// A footprint's diameter grows as the fourth root of its energy past this many pixel values (a
// bright light looks bigger, as it does to the eye and to a camera), from the minimum size.
inline constexpr double kBloomEnergy = 2.0;
// The largest footprint radius, pixels.
inline constexpr double kMaxFootprintPx = 64.0;

struct LightPassStats {
  size_t drawn = 0;     // lights whose footprint reached the frame with some energy
  size_t occluded = 0;  // of those, the ones some polygon was nearer than over their footprint
  double ms = 0;
};

// Adds the scene's light points to `image` (the pixels of `region` of the frame `geometry` was
// projected for), at scene time `settings.scene_time_s`. `stop` is asked between bands of rows.
absl::Status DrawLightPoints(const Scene& scene, const Camera& camera,
                             const FrameGeometry& geometry, const RenderSettings& settings,
                             const PixelRect& region, Image& image, LightPassStats* stats,
                             const StopRequested& stop = {});

}  // namespace aperture
