// The covered share of a light point's footprint, computed apart from the renderer: the footprint
// as docs/SCENE.md describes it (the regular octagon of its disc's area, vertices at (k + 1/2) 45
// degrees) clipped by a convex screen polygon (Sutherland-Hodgman), for the light benchmarks and
// the light-behind-an-edge test.
#pragma once

#include <cmath>
#include <utility>
#include <vector>

#include "scene/vec.h"

namespace aperture::testing {

// The signed area (the shoelace formula): positive counter-clockwise in a y-up frame.
inline double ShoelaceArea(const std::vector<Vec2>& polygon) {
  double twice = 0;
  for (size_t i = 0; i < polygon.size(); ++i) {
    const Vec2& a = polygon[i];
    const Vec2& b = polygon[(i + 1) % polygon.size()];
    twice += a.x * b.y - b.x * a.y;
  }
  return 0.5 * twice;
}

// The regular octagon of the area of the disc of `radius` centred at (x, y).
inline std::vector<Vec2> FootprintOctagon(double x, double y, double radius) {
  // A regular octagon of circumradius R has area 2 sqrt(2) R^2 = pi radius^2.
  const double circumradius = radius * std::sqrt(M_PI / (2 * std::sqrt(2.0)));
  std::vector<Vec2> v;
  for (int k = 0; k < 8; ++k) {
    const double a = (k + 0.5) * M_PI / 4;
    v.push_back({x + circumradius * std::cos(a), y + circumradius * std::sin(a)});
  }
  return v;
}

// The area of convex `subject` inside convex `clip` (either orientation).
inline double ClippedArea(std::vector<Vec2> subject, const std::vector<Vec2>& clip) {
  const double orientation = ShoelaceArea(clip) > 0 ? 1 : -1;
  for (size_t e = 0; e < clip.size() && !subject.empty(); ++e) {
    const Vec2 a = clip[e], b = clip[(e + 1) % clip.size()];
    auto side = [&](const Vec2& p) {
      return orientation * ((b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x));
    };
    std::vector<Vec2> kept;
    for (size_t i = 0; i < subject.size(); ++i) {
      const Vec2 p = subject[i], q = subject[(i + 1) % subject.size()];
      const double sp = side(p), sq = side(q);
      if (sp >= 0) kept.push_back(p);
      if ((sp >= 0) != (sq >= 0)) {
        const double t = sp / (sp - sq);
        kept.push_back({p.x + t * (q.x - p.x), p.y + t * (q.y - p.y)});
      }
    }
    subject = std::move(kept);
  }
  return subject.size() < 3 ? 0 : std::abs(ShoelaceArea(subject));
}

// The share of the footprint at (x, y) of `radius` that convex `occluder` leaves visible.
inline double VisibleFootprintShare(double x, double y, double radius,
                                    const std::vector<Vec2>& occluder) {
  const std::vector<Vec2> octagon = FootprintOctagon(x, y, radius);
  return 1 - ClippedArea(octagon, occluder) / std::abs(ShoelaceArea(octagon));
}

}  // namespace aperture::testing
