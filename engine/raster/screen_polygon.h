// A polygon after projection: convex, in screen pixels (x right, y down, pixel centres at +0.5),
// with the screen-linear functions of seed 000 eq. 1 for depth and texture coordinates.
#pragma once

#include <vector>

#include "absl/container/inlined_vector.h"
#include "base/image.h"
#include "scene/vec.h"

namespace aperture {

// f(x, y) = a x + b y + c over the screen.
struct ScreenLinear {
  double a = 0, b = 0, c = 0;
  double At(double x, double y) const { return a * x + b * y + c; }
};

struct ScreenPolygon {
  // (The box, area and perimeter come first, in one cache line with the start of the vertices:
  // planning a crowded frame reads just these of every polygon, for each window it reaches.)
  double min_x = 0, min_y = 0, max_x = 0, max_y = 0;
  // Its area and the sum of its edges' lengths, in pixels: what the cost model measures of a
  // polygon wholly inside a window (cost/window_cost.h), kept so that planning a crowded frame
  // does not read every polygon's vertices again for each window.
  double area = 0, perimeter = 0;
  // Convex, counter-clockwise in screen space (y down). Held in place up to a quad: a frame of a
  // million triangles would otherwise make two million heap blocks and free them one by one.
  absl::InlinedVector<Vec2, 4> vertices;
  // 1 / view depth: the denominator of seed 000 eq. 1. Larger is nearer.
  ScreenLinear inv_depth;
  // seed 000, eq. 1: U = u_num / inv_depth, V = v_num / inv_depth (texture repeats, shifted by
  // whole periods so that U, V stay small near the camera).
  ScreenLinear u_num, v_num;
  int material = 0;
  int scene_polygon = 0;
  // Its object's layer: of two coplanar polygons, the higher layer is drawn over the lower
  // (raster/depth_order.h).
  int layer = 0;
  // Its material has an alpha mode (MASK or BLEND): it hides nothing for certain, so it is never
  // a window's cover and cells composite what lies behind it (render/leaf_renderer).
  bool transparent = false;
  Rgba light{1, 1, 1, 1};  // ambient + sun * cos(angle), constant over a flat polygon

  // Sets the bounding box, area and perimeter from `vertices` (call after filling them).
  void Finalize();
  // Edge i's function (vertex i to i + 1), >= 0 inside: e(x, y) = cross(q - p, (x, y) - p).
  // Computed from the vertices when asked, not stored: a third of the polygon's size, which a
  // frame of 100,000 triangles writes into fresh memory and joins serially.
  ScreenLinear Edge(size_t i) const {
    const Vec2& p = vertices[i];
    const Vec2& q = vertices[i + 1 == vertices.size() ? 0 : i + 1];
    const double dx = q.x - p.x, dy = q.y - p.y;
    return {-dy, dx, dy * p.x - dx * p.y};
  }
  bool Contains(double x, double y) const {
    for (size_t i = 0; i < vertices.size(); ++i)
      if (Edge(i).At(x, y) < 0) return false;
    return true;
  }
  // Holds the whole rectangle [x0, x1] x [y0, y1]: its four corners (convex). Only a polygon
  // whose box holds the rectangle can, which is tested first.
  bool ContainsRect(double x0, double y0, double x1, double y1) const {
    if (min_x > x0 || max_x < x1 || min_y > y0 || max_y < y1) return false;
    return Contains(x0, y0) && Contains(x1, y0) && Contains(x1, y1) && Contains(x0, y1);
  }
};

}  // namespace aperture
