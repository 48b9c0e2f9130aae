#include "trace/projection_integral.h"

#include <algorithm>
#include <cmath>

#include "trace/polygon_integral.h"

namespace aperture {

bool ProjectionIntegrator::ExactMean(const std::array<TexPoint, 4>& q, const TextureIntegral& sat,
                                     std::array<double, 4>* mean, int* base_steps,
                                     FragmentStats* stats) const {
  if (base_steps) *base_steps = 0;
  const SummedAreaTable* base = sat.table(0);
  const int budget = options_.exact_steps;
  if (base == nullptr || budget <= 0) return false;
  int steps = 0;
  if (PolygonMean(q, *base, budget, mean, &steps)) {
    if (stats) stats->exact += 1, stats->exact_steps += steps;
    return true;
  }
  if (base_steps) *base_steps = steps;
  return false;
}

void ProjectionIntegrator::CoarseMean(const std::array<TexPoint, 4>& q, const TextureIntegral& sat,
                                      int base_steps, std::array<double, 4>* mean,
                                      FragmentStats* stats) const {
  // The finest mip level whose exact integral fits the work budget: about the base's steps
  // halved per level.
  const int budget = options_.exact_steps;
  int steps = 0;
  int level = std::max(1, static_cast<int>(std::ceil(std::log2(double(base_steps) / budget))));
  for (; sat.table(level) != nullptr; ++level)
    if (PolygonMean(q, *sat.table(level), budget, mean, &steps)) break;
  if (sat.table(level) == nullptr) {
    // Not even the coarsest table (2 texels on a side) fits: a projection over thousands of
    // periods, whose mean is the texture's own (the last mip level, one texel).
    level = 0;
    while (sat.table(level) != nullptr) ++level;
    const SummedAreaTable& base = *sat.table(0);
    double whole[4];
    base.Corner(base.width() - 0.5, base.height() - 0.5, whole);
    const double inv = 1.0 / (double(base.width()) * base.height());
    *mean = {};
    for (int c = 0; c < base.channels(); ++c) (*mean)[c] = whole[c] * inv;
    steps = 0;
  }
  if (stats) {
    stats->exact += 1, stats->exact_steps += steps;
    stats->coarse += 1, stats->coarse_level_sum += level;
  }
}

Rgba ProjectionIntegrator::Color(const std::array<TexPoint, 4>& quad, const TextureIntegral& sat,
                                 FragmentStats* stats) {
  // Move the quad by whole periods next to the origin (the texture is periodic), so that its
  // coordinates keep their precision however far the surface runs.
  const double sx = std::floor(quad[0].x), sz = std::floor(quad[0].z);
  std::array<TexPoint, 4> q = quad;
  for (TexPoint& p : q) p.x -= sx, p.z -= sz;
  auto colour = [](const std::array<double, 4>& m) {
    return Rgba{static_cast<float>(m[0]), static_cast<float>(m[1]), static_cast<float>(m[2]),
                static_cast<float>(m[3])};
  };
  std::array<double, 4> mean;
  int base_steps = 0;
  if (ExactMean(q, sat, &mean, &base_steps, stats)) return colour(mean);
  BuildFragments(q, options_, &set_);
  // Fragments that miss eq. 9's bound (their work cap stopped them: a thin projection slanted
  // across many texels, near the horizon) would be integrated at their cost for an error over
  // delta: the exact integral of a coarser mip level instead, within the exact integral's budget.
  if (base_steps > options_.exact_steps && set_.area > set_.quad_area * (1 + options_.delta)) {
    CoarseMean(q, sat, base_steps, &mean, stats);
    return colour(mean);
  }

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
