// The one quadrant split of a window, shared by Warnock's subdivision (raster/warnock.h) and the
// cost-driven task planner (cost/task_planner.h), so that both cut a window the same way.
#pragma once

#include "base/pixel_rect.h"

namespace aperture {

// Up to four quadrants, in the order top-left, top-right, bottom-left, bottom-right, empty ones
// left out.
struct WindowQuadrants {
  PixelRect rects[4];
  int count = 0;
  const PixelRect* begin() const { return rects; }
  const PixelRect* end() const { return rects + count; }
  bool empty() const { return count == 0; }
};

// Each side of `window` longer than `max_side` is halved at its start + length / 2; a side at
// most `max_side` long stays whole, so a long thin window splits in two. None when neither side
// is longer than `max_side`: the window is a leaf.
WindowQuadrants SplitWindow(const PixelRect& window, int max_side);

}  // namespace aperture
