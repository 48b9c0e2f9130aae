#include "raster/warnock.h"

#include <tbb/parallel_for.h>

#include <algorithm>

namespace aperture {
namespace {

struct Rect {
  double x0, y0, x1, y1;
};

// Does convex `p` reach into rectangle `r`? Bounding boxes, then the polygon's edges as
// separating axes (the rectangle's own axes are the bounding-box test).
bool Overlaps(const ScreenPolygon& p, const Rect& r) {
  if (p.max_x <= r.x0 || p.min_x >= r.x1 || p.max_y <= r.y0 || p.min_y >= r.y1) return false;
  const size_t n = p.vertices.size();
  for (size_t i = 0; i < n; ++i) {
    const Vec2& a = p.vertices[i];
    const Vec2& b = p.vertices[(i + 1) % n];
    const double ex = b.x - a.x, ey = b.y - a.y;
    auto inside = [&](double x, double y) { return ex * (y - a.y) - ey * (x - a.x) > 0; };
    if (!inside(r.x0, r.y0) && !inside(r.x1, r.y0) && !inside(r.x1, r.y1) && !inside(r.x0, r.y1))
      return false;
  }
  return true;
}

class Subdivider {
 public:
  Subdivider(const FrameGeometry& g, const AaFilterShape& aa, const WarnockOptions& o)
      : geo_(g), aa_(aa), options_(o) {}

  void Run(const PixelRect& rect, const std::vector<int>& candidates,
           std::vector<LeafWindow>& leaves) const {
    const Rect influence{rect.x0 - aa_.margin, rect.y0 - aa_.margin, rect.x1 + aa_.margin,
                         rect.y1 + aa_.margin};
    std::vector<int> inside;
    for (int i : candidates)
      if (Overlaps(geo_.polygons[i], influence)) inside.push_back(i);

    LeafWindow leaf;
    leaf.rect = rect;
    if (inside.empty()) {
      leaves.push_back(std::move(leaf));
      return;
    }
    if (int cover = FrontCover(inside, influence); cover >= 0) {
      leaf.kind = LeafWindow::Kind::kCovered;
      leaf.cover = cover;
      leaves.push_back(std::move(leaf));
      return;
    }
    const bool split_x = rect.width() > options_.leaf_size;
    const bool split_y = rect.height() > options_.leaf_size;
    if (!split_x && !split_y) {
      leaf.kind = LeafWindow::Kind::kMixed;
      leaf.polygons = std::move(inside);
      leaves.push_back(std::move(leaf));
      return;
    }
    const int xm = split_x ? rect.x0 + rect.width() / 2 : rect.x1;
    const int ym = split_y ? rect.y0 + rect.height() / 2 : rect.y1;
    const PixelRect quads[4] = {{rect.x0, rect.y0, xm, ym},
                                {xm, rect.y0, rect.x1, ym},
                                {rect.x0, ym, xm, rect.y1},
                                {xm, ym, rect.x1, rect.y1}};
    for (const PixelRect& q : quads)
      if (q.width() > 0 && q.height() > 0) Run(q, inside, leaves);
  }

 private:
  // A polygon containing the whole influence rectangle and nearer than every other polygon at
  // its four corners (depth differences are screen-linear, so that holds over the rectangle).
  int FrontCover(const std::vector<int>& inside, const Rect& r) const {
    const double xs[4] = {r.x0, r.x1, r.x1, r.x0}, ys[4] = {r.y0, r.y0, r.y1, r.y1};
    for (int c : inside) {
      const ScreenPolygon& p = geo_.polygons[c];
      bool covers = true;
      for (int k = 0; k < 4 && covers; ++k) covers = p.Contains(xs[k], ys[k]);
      if (!covers) continue;
      bool front = true;
      for (int o : inside) {
        if (o == c) continue;
        const ScreenPolygon& q = geo_.polygons[o];
        for (int k = 0; k < 4 && front; ++k)
          front = p.inv_depth.At(xs[k], ys[k]) > q.inv_depth.At(xs[k], ys[k]);
        if (!front) break;
      }
      if (front) return c;
    }
    return -1;
  }

  const FrameGeometry& geo_;
  const AaFilterShape& aa_;
  const WarnockOptions& options_;
};

}  // namespace

std::vector<LeafWindow> SubdivideWarnock(const FrameGeometry& geo, const AaFilterShape& aa,
                                         const PixelRect& region, const WarnockOptions& options) {
  const int root = std::max(options.root_size, options.leaf_size);
  const int cols = (region.width() + root - 1) / root, rows = (region.height() + root - 1) / root;
  if (cols <= 0 || rows <= 0) return {};
  // Bin polygons into root windows by their bounding boxes.
  std::vector<std::vector<int>> bins(static_cast<size_t>(cols) * rows);
  for (size_t i = 0; i < geo.polygons.size(); ++i) {
    const ScreenPolygon& p = geo.polygons[i];
    auto col = [&](double x) {
      return std::clamp(static_cast<int>(std::floor((x - region.x0) / root)), 0, cols - 1);
    };
    auto row = [&](double y) {
      return std::clamp(static_cast<int>(std::floor((y - region.y0) / root)), 0, rows - 1);
    };
    if (p.max_x < region.x0 - aa.margin || p.min_x > region.x1 + aa.margin ||
        p.max_y < region.y0 - aa.margin || p.min_y > region.y1 + aa.margin)
      continue;
    for (int r = row(p.min_y - aa.margin); r <= row(p.max_y + aa.margin); ++r)
      for (int c = col(p.min_x - aa.margin); c <= col(p.max_x + aa.margin); ++c)
        bins[static_cast<size_t>(r) * cols + c].push_back(static_cast<int>(i));
  }
  std::vector<std::vector<LeafWindow>> per_root(bins.size());
  const Subdivider subdivider(geo, aa, options);
  tbb::parallel_for(size_t{0}, bins.size(), [&](size_t k) {
    const int r = static_cast<int>(k) / cols, c = static_cast<int>(k) % cols;
    const PixelRect rect{region.x0 + c * root, region.y0 + r * root,
                         std::min(region.x1, region.x0 + (c + 1) * root),
                         std::min(region.y1, region.y0 + (r + 1) * root)};
    subdivider.Run(rect, bins[k], per_root[k]);
  });
  std::vector<LeafWindow> leaves;
  for (auto& v : per_root)
    for (auto& leaf : v) leaves.push_back(std::move(leaf));
  return leaves;
}

}  // namespace aperture
