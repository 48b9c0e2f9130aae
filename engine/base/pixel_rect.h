// A rectangle of pixels: a frame's region, a Warnock window, a render task.
#pragma once

namespace aperture {

struct PixelRect {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // [x0, x1) x [y0, y1)
  int width() const { return x1 - x0; }
  int height() const { return y1 - y0; }
  long long pixels() const { return static_cast<long long>(width()) * height(); }
};

}  // namespace aperture
