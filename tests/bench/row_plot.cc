#include "bench/row_plot.h"

#include <algorithm>
#include <cmath>

namespace aperture {
namespace {

// A line from (x0, y0) to (x1, y1), one pixel wide, by steps along its longer extent.
void DrawLine(Image& image, double x0, double y0, double x1, double y1, const Rgba& colour) {
  const int steps = static_cast<int>(std::ceil(std::max(std::abs(x1 - x0), std::abs(y1 - y0)))) + 1;
  for (int s = 0; s <= steps; ++s) {
    const double t = static_cast<double>(s) / steps;
    const int x = static_cast<int>(std::lround(x0 + t * (x1 - x0)));
    const int y = static_cast<int>(std::lround(y0 + t * (y1 - y0)));
    if (x >= 0 && y >= 0 && x < image.width() && y < image.height()) image.at(x, y) = colour;
  }
}

}  // namespace

Image PlotRows(const std::vector<PlotSeries>& series, int first, int width, int height) {
  Image image(width, height, {1, 1, 1, 1});
  double lo = INFINITY, hi = -INFINITY;
  size_t rows = 0;
  for (const PlotSeries& s : series) {
    rows = std::max(rows, s.values.size());
    for (size_t r = first; r < s.values.size(); ++r)
      if (std::isfinite(s.values[r]))
        lo = std::min(lo, s.values[r]), hi = std::max(hi, s.values[r]);
  }
  if (!(lo <= hi) || rows <= static_cast<size_t>(first) + 1) return image;
  lo = 10 * std::floor(lo / 10), hi = 10 * std::ceil(hi / 10);
  if (hi == lo) hi = lo + 10;
  const double x_scale = (width - 1.0) / (static_cast<double>(rows) - 1 - first);
  const double y_scale = (height - 1.0) / (hi - lo);
  auto y_of = [&](double v) { return (height - 1.0) - (v - lo) * y_scale; };
  for (double v = lo; v <= hi; v += 10)
    DrawLine(image, 0, y_of(v), width - 1, y_of(v), {0.8f, 0.8f, 0.8f, 1});
  for (const PlotSeries& s : series) {
    bool have_previous = false;
    double px = 0, py = 0;
    for (size_t r = first; r < s.values.size(); ++r) {
      if (!std::isfinite(s.values[r])) {
        have_previous = false;
        continue;
      }
      const double x = (static_cast<double>(r) - first) * x_scale, y = y_of(s.values[r]);
      if (have_previous) DrawLine(image, px, py, x, y, s.colour);
      px = x, py = y, have_previous = true;
    }
  }
  return image;
}

}  // namespace aperture
