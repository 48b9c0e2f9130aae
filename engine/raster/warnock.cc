#include "raster/warnock.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "raster/depth_order.h"
#include "raster/window_quadrants.h"

namespace aperture {
namespace {

struct Rect {
  double x0, y0, x1, y1;
};

// Does convex `p` reach into rectangle `r`? Bounding boxes, then the polygon's edges as
// separating axes (the rectangle's own axes are the bounding-box test).
bool Overlaps(const ScreenPolygon& p, const Rect& r) {
  return PolygonOverlapsRect(p, r.x0, r.y0, r.x1, r.y1);
}

}  // namespace

bool PolygonOverlapsRect(const ScreenPolygon& p, double x0, double y0, double x1, double y1) {
  const Rect r{x0, y0, x1, y1};
  if (p.max_x <= r.x0 || p.min_x >= r.x1 || p.max_y <= r.y0 || p.min_y >= r.y1) return false;
  // A box inside the rectangle (by a margin far above rounding) overlaps it: every edge then has
  // a corner strictly on its inner side, as the test below would find. The small polygons of a
  // crowded window are mostly such.
  constexpr double kMargin = 1e-6;
  if (p.min_x > r.x0 + kMargin && p.max_x < r.x1 - kMargin && p.min_y > r.y0 + kMargin &&
      p.max_y < r.y1 - kMargin)
    return true;
  const size_t n = p.vertices.size();
  for (size_t i = 0; i < n; ++i) {
    const Vec2& a = p.vertices[i];
    const Vec2& b = p.vertices[i + 1 == n ? 0 : i + 1];
    const double ex = b.x - a.x, ey = b.y - a.y;
    auto inside = [&](double x, double y) { return ex * (y - a.y) - ey * (x - a.x) > 0; };
    if (!inside(r.x0, r.y0) && !inside(r.x1, r.y0) && !inside(r.x1, r.y1) && !inside(r.x0, r.y1))
      return false;
  }
  return true;
}

namespace {

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
    const int leaf_size = static_cast<int>(inside.size()) > options_.crowded_polygons
                              ? std::max(options_.leaf_size, options_.crowded_leaf_size)
                              : options_.leaf_size;
    const WindowQuadrants quads = SplitWindow(rect, leaf_size);
    if (quads.empty()) {
      leaf.kind = LeafWindow::Kind::kMixed;
      leaf.polygons = std::move(inside);
      leaves.push_back(std::move(leaf));
      return;
    }
    for (const PixelRect& q : quads) Run(q, inside, leaves);
  }

 private:
  // An opaque polygon containing the whole influence rectangle that hides every other polygon
  // there (raster/depth_order.h, at the rectangle's corners: depth differences are
  // screen-linear). Only the one nearest at the centre can be it; found, then checked: each
  // polygon is looked at twice, however many coplanar layers are stacked in the window.
  int FrontCover(const std::vector<int>& inside, const Rect& r) const {
    const double xc = 0.5 * (r.x0 + r.x1), yc = 0.5 * (r.y0 + r.y1);
    int cover = -1;
    double nearest = 0;
    for (int c : inside) {
      const ScreenPolygon& p = geo_.polygons[c];
      if (p.transparent) continue;  // what lies behind it may show through
      const double w = p.inv_depth.At(xc, yc);
      if (cover >= 0) {
        const int s = DepthSign(w, nearest);
        if (s < 0 || (s == 0 && DrawOrder(p.layer, c) < Order(cover))) continue;
      }
      if (!p.ContainsRect(r.x0, r.y0, r.x1, r.y1)) continue;
      cover = c, nearest = w;
    }
    if (cover < 0) return -1;
    const ScreenPolygon& front = geo_.polygons[cover];
    const double xs[4] = {r.x0, r.x1, r.x1, r.x0}, ys[4] = {r.y0, r.y0, r.y1, r.y1};
    for (int o : inside) {
      if (o == cover) continue;
      const ScreenPolygon& q = geo_.polygons[o];
      int signs[4];
      for (int k = 0; k < 4; ++k)
        signs[k] = DepthSign(front.inv_depth.At(xs[k], ys[k]), q.inv_depth.At(xs[k], ys[k]));
      if (!HidesAt(signs, Order(cover) > DrawOrder(q.layer, o))) return -1;
    }
    return cover;
  }
  int64_t Order(int polygon) const { return DrawOrder(geo_.polygons[polygon].layer, polygon); }

  const FrameGeometry& geo_;
  const AaFilterShape& aa_;
  const WarnockOptions& options_;
};

}  // namespace

std::vector<std::vector<int>> BinPolygons(const FrameGeometry& geo, double margin,
                                          const PixelRect& region, int tile, int* columns) {
  const int cols = (region.width() + tile - 1) / tile, rows = (region.height() + tile - 1) / tile;
  *columns = std::max(cols, 0);
  if (cols <= 0 || rows <= 0) return {};
  const size_t tiles = static_cast<size_t>(cols) * rows;
  auto col = [&](double x) {
    return std::clamp(static_cast<int>(std::floor((x - region.x0) / tile)), 0, cols - 1);
  };
  auto row = [&](double y) {
    return std::clamp(static_cast<int>(std::floor((y - region.y0) / tile)), 0, rows - 1);
  };
  // Fixed chunks of the polygons binned in parallel, each chunk's bins joined in chunk order: every
  // bin lists its polygons in ascending order, whatever the threads.
  constexpr size_t kChunk = 1 << 16;
  const size_t count = geo.polygons.size();
  const size_t chunks = std::max<size_t>(1, (count + kChunk - 1) / kChunk);
  std::vector<std::vector<std::vector<int>>> parts(chunks);
  tbb::parallel_for(size_t{0}, chunks, [&](size_t k) {
    std::vector<std::vector<int>>& bins = parts[k];
    bins.resize(tiles);
    for (size_t i = k * kChunk; i < std::min(count, (k + 1) * kChunk); ++i) {
      const ScreenPolygon& p = geo.polygons[i];
      if (p.max_x < region.x0 - margin || p.min_x > region.x1 + margin ||
          p.max_y < region.y0 - margin || p.min_y > region.y1 + margin)
        continue;
      for (int r = row(p.min_y - margin); r <= row(p.max_y + margin); ++r)
        for (int c = col(p.min_x - margin); c <= col(p.max_x + margin); ++c)
          bins[static_cast<size_t>(r) * cols + c].push_back(static_cast<int>(i));
    }
  });
  if (chunks == 1) return std::move(parts[0]);
  std::vector<std::vector<int>> bins(tiles);
  tbb::parallel_for(size_t{0}, tiles, [&](size_t t) {
    size_t total = 0;
    for (const auto& part : parts) total += part[t].size();
    bins[t].reserve(total);
    for (const auto& part : parts) bins[t].insert(bins[t].end(), part[t].begin(), part[t].end());
  });
  return bins;
}

void SubdivideWindow(const FrameGeometry& geo, const AaFilterShape& aa,
                     const WarnockOptions& options, const PixelRect& window,
                     const std::vector<int>& candidates, std::vector<LeafWindow>& leaves) {
  Subdivider(geo, aa, options).Run(window, candidates, leaves);
}

}  // namespace aperture
