#include "support/reference_render.h"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "raster/depth_order.h"

namespace aperture::testing {

Camera OriginCamera() {
  Camera c;  // at the origin looking along -z
  c.vertical_fov_deg = 60;
  return c;
}

Vec3 PointAtPixel(int width, int height, double px, double py, double depth) {
  const FrustumTangents f = ResolveFrustum(OriginCamera(), width, height);
  const double x = f.left + px / width * (f.right - f.left);
  const double y = f.top - py / height * (f.top - f.bottom);
  return {x * depth, y * depth, -depth};
}

namespace {

// Calls sample(x, y, weight) at n x n stratified points over pixel (px, py)'s aperture.
template <typename Sample>
void ForEachSample(AntiAliasing aa, int px, int py, int n, Sample sample) {
  const double half = aa == AntiAliasing::kBox1 ? 0.5 : 1.0;  // aperture half-width
  const double cx = px + 0.5, cy = py + 0.5;
  for (int j = 0; j < n; ++j) {
    const double dy = -half + (j + 0.5) * (2 * half / n);
    for (int i = 0; i < n; ++i) {
      const double dx = -half + (i + 0.5) * (2 * half / n);
      const double w = aa == AntiAliasing::kTent2 ? (1 - std::abs(dx)) * (1 - std::abs(dy)) : 1.0;
      sample(cx + dx, cy + dy, w);
    }
  }
}

}  // namespace

Rgba DenseReferencePixel(const FrameGeometry& geo, const FlatColour& colour, Rgba sky,
                         AntiAliasing aa, int px, int py, int n) {
  double r = 0, g = 0, b = 0, total = 0;
  ForEachSample(aa, px, py, n, [&](double x, double y, double w) {
    int best = -1;
    double best_depth = 0;
    for (size_t k = 0; k < geo.polygons.size(); ++k) {
      const ScreenPolygon& p = geo.polygons[k];
      if (x < p.min_x || x > p.max_x || y < p.min_y || y > p.max_y || !p.Contains(x, y)) continue;
      const double d = p.inv_depth.At(x, y);
      const int sign = best < 0 ? 1 : DepthSign(d, best_depth);
      if (sign > 0 || (sign == 0 && DrawOrder(p.layer, static_cast<int>(k)) >
                                        DrawOrder(geo.polygons[best].layer, best)))
        best = static_cast<int>(k), best_depth = d;
    }
    const Rgba c = best < 0 ? sky : colour(best);
    r += w * c.r, g += w * c.g, b += w * c.b;
    total += w;
  });
  return {static_cast<float>(r / total), static_cast<float>(g / total),
          static_cast<float>(b / total), 1.0f};
}

Rgba DenseCompositedPixel(const FrameGeometry& geo, const FlatColour& colour, Rgba sky,
                          AntiAliasing aa, int px, int py, int n) {
  double r = 0, g = 0, b = 0, a = 0, total = 0;
  std::vector<std::pair<double, int>> hits;  // (1 / depth, polygon)
  ForEachSample(aa, px, py, n, [&](double x, double y, double w) {
    hits.clear();
    for (size_t k = 0; k < geo.polygons.size(); ++k) {
      const ScreenPolygon& p = geo.polygons[k];
      if (x < p.min_x || x > p.max_x || y < p.min_y || y > p.max_y || !p.Contains(x, y)) continue;
      hits.push_back({p.inv_depth.At(x, y), static_cast<int>(k)});
    }
    // Front to back; coplanar surfaces (equal within the tolerance) by the order they are drawn.
    // (A selection: the tolerance makes "in front" no strict weak order for std::sort.)
    auto over = [&](const std::pair<double, int>& u, const std::pair<double, int>& v) {
      const int sign = DepthSign(u.first, v.first);
      return sign > 0 || (sign == 0 && DrawOrder(geo.polygons[u.second].layer, u.second) >
                                           DrawOrder(geo.polygons[v.second].layer, v.second));
    };
    for (size_t i = 0; i < hits.size(); ++i)
      for (size_t j = i + 1; j < hits.size(); ++j)
        if (over(hits[j], hits[i])) std::swap(hits[i], hits[j]);
    double transmitted = 1, sr = 0, sg = 0, sb = 0, sa = 0;
    for (const auto& [depth, k] : hits) {
      const Rgba c = colour(k);
      const double alpha = std::clamp<double>(c.a, 0, 1);
      sr += transmitted * alpha * c.r, sg += transmitted * alpha * c.g;
      sb += transmitted * alpha * c.b, sa += transmitted * alpha;
      transmitted *= 1 - alpha;
      if (transmitted == 0) break;
    }
    sr += transmitted * sky.r, sg += transmitted * sky.g, sb += transmitted * sky.b;
    sa += transmitted * sky.a;
    r += w * sr, g += w * sg, b += w * sb, a += w * sa;
    total += w;
  });
  return {static_cast<float>(r / total), static_cast<float>(g / total),
          static_cast<float>(b / total), static_cast<float>(a / total)};
}

}  // namespace aperture::testing
