#include "trace/projection_integral.h"

#include <cmath>

#include "trace/polygon_integral.h"

namespace aperture {

Rgba ProjectionIntegrator::Color(const std::array<TexPoint, 4>& quad, const TextureIntegral& sat,
                                 FragmentStats* stats) {
  // Move the quad by whole periods next to the origin (the texture is periodic), so that its
  // coordinates keep their precision however far the surface runs.
  const double sx = std::floor(quad[0].x), sz = std::floor(quad[0].z);
  std::array<TexPoint, 4> q = quad;
  for (TexPoint& p : q) p.x -= sx, p.z -= sz;
  if (const SummedAreaTable* table = sat.table(); table != nullptr && options_.exact_steps > 0) {
    std::array<double, 4> mean;
    int steps = 0;
    if (PolygonMean(q, *table, options_.exact_steps, &mean, &steps)) {
      if (stats) stats->exact += 1, stats->exact_steps += steps;
      return {static_cast<float>(mean[0]), static_cast<float>(mean[1]), static_cast<float>(mean[2]),
              static_cast<float>(mean[3])};
    }
  }
  BuildFragments(q, options_, &set_);

  const double w = sat.width(), h = sat.height();
  double sum[4] = {};
  if (set_.area <= 0) {
    // No area at all (the four corners on one line or one point): the texture at the centre.
    TexPoint c{0.25 * (q[0].x + q[1].x + q[2].x + q[3].x),
               0.25 * (q[0].z + q[1].z + q[2].z + q[3].z)};
    const double e = 1e-3;
    const auto v = sat.IntegratePeriodic(c.x * w - e, c.z * h - e, c.x * w + e, c.z * h + e);
    const float inv = static_cast<float>(1.0 / (4 * e * e));
    return {static_cast<float>(v[0]) * inv, static_cast<float>(v[1]) * inv,
            static_cast<float>(v[2]) * inv, static_cast<float>(v[3]) * inv};
  }
  // seed 003, eq. 3: each child fragment's weighted colour C* = C S is the table's integral over
  // it (in texel units, hence the division by w h below).
  children_.clear();
  double children = 0;
  for (const TexRect& f : set_.fragments) {
    if (f.x1 - f.x0 > 2 || f.z1 - f.z0 > 2) {
      // A fragment over many unit textures (a pixel near the horizon): its children are whole
      // periods but for the borders, summed without listing them (same integral).
      const auto v = sat.IntegratePeriodic(f.x0 * w, f.z0 * h, f.x1 * w, f.z1 * h);
      for (int k = 0; k < 4; ++k) sum[k] += v[k];
      children += (std::ceil(f.x1) - std::floor(f.x0)) * (std::ceil(f.z1) - std::floor(f.z0));
      continue;
    }
    ChildFragments(f, &children_);
  }
  for (const TexRect& c : children_) {
    const auto v = sat.Integrate(c.x0 * w, c.z0 * h, c.x1 * w, c.z1 * h);
    for (int k = 0; k < 4; ++k) sum[k] += v[k];
  }
  children += static_cast<double>(children_.size());
  if (stats) {
    stats->quads += 1;
    stats->relative_error_sum += set_.area / set_.quad_area - 1;
    stats->fragments += static_cast<double>(set_.fragments.size());
    stats->children += children;
  }
  // seed 003, eq. 4: C = sum of C* over the sum of the fragments' areas.
  const double inv = 1.0 / (set_.area * w * h);
  return {static_cast<float>(sum[0] * inv), static_cast<float>(sum[1] * inv),
          static_cast<float>(sum[2] * inv), static_cast<float>(sum[3] * inv)};
}

}  // namespace aperture
