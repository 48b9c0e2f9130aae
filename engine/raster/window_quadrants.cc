#include "raster/window_quadrants.h"

namespace aperture {

WindowQuadrants SplitWindow(const PixelRect& w, int max_side) {
  WindowQuadrants out;
  const bool split_x = w.width() > max_side, split_y = w.height() > max_side;
  if (!split_x && !split_y) return out;
  const int xm = split_x ? w.x0 + w.width() / 2 : w.x1;
  const int ym = split_y ? w.y0 + w.height() / 2 : w.y1;
  const PixelRect quads[4] = {
      {w.x0, w.y0, xm, ym}, {xm, w.y0, w.x1, ym}, {w.x0, ym, xm, w.y1}, {xm, ym, w.x1, w.y1}};
  for (const PixelRect& q : quads)
    if (q.width() > 0 && q.height() > 0) out.rects[out.count++] = q;
  return out;
}

}  // namespace aperture
