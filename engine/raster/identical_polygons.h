// Identical screen polygons: the same mesh placed twice at one place, or ten thousand objects an
// update moved to one spot. Of such copies only the one drawn last (raster/depth_order.h) can be
// seen where they are opaque, so the visibility code keeps it alone.
#pragma once

#include <cstdint>
#include <cstring>

#include "raster/screen_polygon.h"

namespace aperture {

// The same vertices and the same depth, bit for bit (what placing one mesh twice gives).
inline bool SameScreenPolygon(const ScreenPolygon& a, const ScreenPolygon& b) {
  if (a.vertices.size() != b.vertices.size()) return false;
  for (size_t k = 0; k < a.vertices.size(); ++k)
    if (a.vertices[k].x != b.vertices[k].x || a.vertices[k].y != b.vertices[k].y) return false;
  return a.inv_depth.a == b.inv_depth.a && a.inv_depth.b == b.inv_depth.b &&
         a.inv_depth.c == b.inv_depth.c;
}

// A hash of what SameScreenPolygon compares (FNV-1a over the values' bits).
inline uint64_t ScreenPolygonHash(const ScreenPolygon& p) {
  uint64_t h = 1469598103934665603ull;
  auto mix = [&h](double d) {
    uint64_t bits;
    std::memcpy(&bits, &d, sizeof bits);
    h = (h ^ bits) * 1099511628211ull;
  };
  for (const Vec2& v : p.vertices) mix(v.x), mix(v.y);
  mix(p.inv_depth.a), mix(p.inv_depth.b), mix(p.inv_depth.c);
  return h;
}

}  // namespace aperture
