// The sky behind a frame whose scene's sky varies with direction (a time of day,
// scene/sky_dome.h). The renderers draw such a frame over a transparent sky, then composite this
// under it: each pixel gains the sky times what its surfaces leave uncovered (1 - alpha), the
// same sum a one-colour sky makes inside the renderers. The sky changes slowly across the view,
// so it is evaluated on a grid of the frame's pixel centres every kSkyGridStep pixels and
// interpolated bilinearly between them: a few thousand evaluations of the model per frame.
#pragma once

#include <vector>

#include "base/image.h"
#include "base/pixel_rect.h"
#include "scene/camera.h"
#include "scene/sky_dome.h"

namespace aperture {

constexpr int kSkyGridStep = 8;

class SkyBackdrop {
 public:
  // The sky of `dome` behind `region` of a width x height frame seen by `camera`.
  SkyBackdrop(const SkyDome& dome, const Camera& camera, int width, int height,
              const PixelRect& region);
  // The sky at frame pixel (x, y) of the region (its centre), alpha 1.
  Rgba At(int x, int y) const;
  // The sky at frame pixels [x0, x1) of row y into out[0 .. x1 - x0) (each as At gives it).
  void Row(int y, int x0, int x1, Rgba* out) const;
  // The sky's value at the centre of frame pixel (x, y), evaluated there (no grid).
  static Rgba Exact(const SkyDome& dome, const Camera& camera, int width, int height, int x, int y);

 private:
  int width_ = 0, height_ = 0;  // the frame's
  int i0_ = 0, j0_ = 0;         // the first node's place in the frame's grid
  int columns_ = 0, rows_ = 0;  // grid nodes
  std::vector<Rgba> nodes_;     // row by row
};

// Composites the sky behind `image` (the pixels of `region`, drawn over a transparent sky, RGB
// premultiplied by alpha): each pixel's RGB gains the sky times (1 - alpha), its alpha becomes 1.
// Rows in parallel (the caller's task arena).
void CompositeSky(const SkyDome& dome, const Camera& camera, int width, int height,
                  const PixelRect& region, Image& image);

}  // namespace aperture
