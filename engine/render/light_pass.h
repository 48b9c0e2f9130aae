// Light points drawn over a rendered frame (scene/light_points.h; docs/SCENE.md, "Light points").
//
// Each light's illuminance at the eye, E = I T(d) / d^2 (Allard's law: I its intensity towards the
// eye, T the fog's transmission over its distance d), becomes a pixel-value energy S = exposure x
// E / (the solid angle of one pixel at its place on the screen), spread uniformly over a small
// disc footprint (a regular octagon of the disc's area). The footprint is the light's image, not a
// surface: the polygons seen in its cells whose planes are nearer than the light where it is (at
// the footprint's centre), and that are nearer than it somewhere, hide it by their outlines; the
// others not at all (the ground under a runway light: the view ray meets the light before it). The
// footprint less those outlines is cut into convex pieces (render/visible_footprint.h), whose exact
// area (and moments, for the tent) in each cell is integrated over the pixels' filter apertures
// like any polygon's piece.
// So the sum of a light's pixels is S times the visible share of its footprint, to float rounding,
// wherever it falls inside a pixel; its image's centroid follows its projection continuously; and a
// light sliding behind an edge dims continuously, by exactly the part of its footprint the edge
// covers.
//
// In fog, part of the light scattered on its way forms a halo (the atmospheric point spread
// function of Narasimhan and Nayar, "Shedding Light on the Weather", CVPR 2003: its forward peak
// widens with the optical depth tau): a second, wider disc carrying I (1 - T) / d^2 x
// kHaloForwardShare, of angular radius kHaloDegPerTau x tau (at least twice the light's own).
#pragma once

#include <cmath>
#include <cstddef>
#include <vector>

#include "absl/status/status.h"
#include "base/image.h"
#include "base/pixel_rect.h"
#include "raster/aa_filter.h"
#include "raster/projection.h"
#include "render/frame_memory.h"
#include "render/renderer.h"
#include "render/visible_surfaces.h"
#include "scene/camera.h"
#include "scene/scene.h"

namespace aperture {

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
  size_t drawn = 0;          // footprints (lights, and halos in fog) that reached the frame
  size_t hidden = 0;         // of those, the ones polygons in front hide wholly
  size_t partly_hidden = 0;  // and those they hide in part
  double ms = 0;             // the pass
};

// A regular octagon of a disc's area (2 sqrt(2) R^2 = pi r^2) has circumradius R = 1.0547 r.
inline constexpr double kOctagonCircumradius = 1.0547;

// A light's image on the screen: a disc of `radius` pixels at (x, y) (drawn as the regular
// octagon of its area) at the light's depth, carrying `r, g, b` pixel values per square pixel.
struct LightFootprint {
  double x, y, radius;
  double inv_depth;  // 1 / view depth, as ScreenPolygon::inv_depth
  float r, g, b;
  // The cells (raster/aa_filter.h's grid) its octagon reaches.
  int CellX0(const AaFilterShape& s) const { return Cell(x - Extent(), s); }
  int CellX1(const AaFilterShape& s) const { return Cell(x + Extent(), s); }
  int CellY0(const AaFilterShape& s) const { return Cell(y - Extent(), s); }
  int CellY1(const AaFilterShape& s) const { return Cell(y + Extent(), s); }

 private:
  // The octagon's circumradius, and a rounding allowance.
  double Extent() const { return radius * kOctagonCircumradius + 1e-6; }
  static int Cell(double v, const AaFilterShape& s) {
    return static_cast<int>(std::floor(v - s.cell_offset));
  }
};

// The footprints of the scene's light points (and their halos in fog) that reach the frame
// `geometry` was projected for, at scene time `settings.scene_time_s`.
std::vector<LightFootprint> ProjectLightPoints(const Scene& scene, const Camera& camera,
                                               const FrameGeometry& geometry,
                                               const RenderSettings& settings);

// Marks the cells the footprints reach wanted in `surfaces`, before the raster pass records them.
void WantLightCells(const std::vector<LightFootprint>& footprints, const AaFilterShape& shape,
                    VisibleSurfaces& surfaces);

// Adds the footprints to `image` (the pixels of `region` of the frame `geometry` was projected
// for). `surfaces` (may be null): what the raster pass saw in the footprints' cells, where a
// light's possible occluders are read; for a footprint whose cells were not all recorded, the
// polygons are binned by tile and searched, those lists held against `memory` (may be null).
// `stop` is asked between bands of rows.
absl::Status DrawLightPoints(const FrameGeometry& geometry, const RenderSettings& settings,
                             const PixelRect& region, const std::vector<LightFootprint>& footprints,
                             Image& image, const VisibleSurfaces* surfaces, FrameMemory* memory,
                             LightPassStats* stats, const StopRequested& stop = {});

}  // namespace aperture
