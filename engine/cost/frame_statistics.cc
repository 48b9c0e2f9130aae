#include "cost/frame_statistics.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <cmath>
#include <functional>

#include "cost/polygons_per_aperture.h"
#include "raster/polygon_clip.h"
#include "scene/triangulate.h"

namespace aperture {

FrameStatistics ComputeFrameStatistics(const FrameGeometry& geo, double aperture) {
  FrameStatistics stats;
  stats.aperture = aperture;
  stats.image_side = std::sqrt(static_cast<double>(geo.width) * geo.height);
  std::vector<Vec2> poly, scratch;
  double area_sum = 0, weighted_l = 0, sqrt_sum = 0;
  for (size_t i = 0; i < geo.polygons.size(); ++i) {
    poly.assign(geo.polygons[i].vertices.begin(), geo.polygons[i].vertices.end());
    ClipToRect(poly, 0, 0, geo.width, geo.height, scratch);
    if (poly.empty()) continue;
    const double area = std::abs(SignedArea(poly));
    if (area <= 0) continue;
    double perimeter = 0;
    for (size_t k = 0; k < poly.size(); ++k) {
      const Vec2& p = poly[k];
      const Vec2& q = poly[(k + 1) % poly.size()];
      perimeter += std::hypot(q.x - p.x, q.y - p.y);
    }
    const double l = ShapeFactor(area, perimeter);
    stats.per_face.push_back({static_cast<int>(i), area, perimeter, l});
    area_sum += area;
    weighted_l += l * std::sqrt(area);
    sqrt_sum += std::sqrt(area);
  }
  stats.faces = static_cast<int>(stats.per_face.size());
  const double m = stats.image_side;
  stats.kappa = area_sum / (m * m);
  stats.mean_shape_factor = sqrt_sum > 0 ? weighted_l / sqrt_sum : 0;
  stats.predicted_square =
      PolygonsPerApertureSquare(stats.kappa, aperture, m, stats.mean_shape_factor, stats.faces);
  stats.predicted_circle =
      PolygonsPerApertureCircle(stats.kappa, aperture, m, stats.mean_shape_factor, stats.faces);
  return stats;
}

double MeasurePolygonsPerAperture(const FrameGeometry& geo, double aperture) {
  const double half = aperture / 2;
  const long long hits = tbb::parallel_reduce(
      tbb::blocked_range<size_t>(0, geo.polygons.size()), 0LL,
      [&](const tbb::blocked_range<size_t>& range, long long count) {
        for (size_t i = range.begin(); i != range.end(); ++i) {
          const ScreenPolygon& p = geo.polygons[i];
          // Pixels whose aperture [cx - half, cx + half] can reach the polygon.
          const int x0 = std::max(0, static_cast<int>(std::floor(p.min_x - half - 0.5)));
          const int x1 = std::min(geo.width - 1, static_cast<int>(std::ceil(p.max_x + half - 0.5)));
          const int y0 = std::max(0, static_cast<int>(std::floor(p.min_y - half - 0.5)));
          const int y1 =
              std::min(geo.height - 1, static_cast<int>(std::ceil(p.max_y + half - 0.5)));
          for (int y = y0; y <= y1; ++y) {
            for (int x = x0; x <= x1; ++x) {
              const double cx = x + 0.5, cy = y + 0.5;
              if (p.max_x <= cx - half || p.min_x >= cx + half || p.max_y <= cy - half ||
                  p.min_y >= cy + half)
                continue;
              // Separating axes: the polygon's edges (the square's are the bounding box).
              bool separated = false;
              for (size_t k = 0; k < p.vertices.size(); ++k) {
                const ScreenLinear e = p.Edge(k);
                if (e.At(cx, cy) + half * (std::abs(e.a) + std::abs(e.b)) <= 0) {
                  separated = true;
                  break;
                }
              }
              if (!separated) ++count;
            }
          }
        }
        return count;
      },
      std::plus<long long>());
  return static_cast<double>(hits) / (static_cast<double>(geo.width) * geo.height);
}

}  // namespace aperture
