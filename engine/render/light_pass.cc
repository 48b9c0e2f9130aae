#include "render/light_pass.h"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <climits>
#include <cmath>
#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include "base/held_bytes.h"
#include "base/stopwatch.h"
#include "raster/cell_coverage.h"
#include "raster/polygon_moments.h"
#include "raster/warnock.h"
#include "render/visible_footprint.h"
#include "scene/object_placement.h"
#include "scene/triangulate.h"

namespace aperture {
namespace {

using Footprint = LightFootprint;

// Rec. 709 luminance of a colour.
double Luminance(double r, double g, double b) { return 0.2126 * r + 0.7152 * g + 0.0722 * b; }

// The octagon whose area is the disc's, edges along the axes and diagonals, counter-clockwise on
// the screen (y down), as ScreenPolygon keeps its vertices.
std::array<Vec2, 8> OctagonVertices(const Footprint& f) {
  // A regular octagon of circumradius R has area 2 sqrt(2) R^2; its vertices at (k + 1/2) 45
  // degrees, in the order of positive signed area on the screen.
  static const std::array<Vec2, 8> kUnit = [] {
    std::array<Vec2, 8> v;
    const double r = std::sqrt(kPi / (2 * std::sqrt(2.0)));
    for (int k = 0; k < 8; ++k)
      v[k] = {r * std::cos((k + 0.5) * kPi / 4), r * std::sin((k + 0.5) * kPi / 4)};
    if (SignedArea(v) < 0) std::reverse(v.begin(), v.end());
    return v;
  }();
  std::array<Vec2, 8> v;
  for (int k = 0; k < 8; ++k) v[k] = {f.x + f.radius * kUnit[k].x, f.y + f.radius * kUnit[k].y};
  return v;
}

// The octagon as a polygon at the light's depth, for the cell-by-cell resolution.
ScreenPolygon Octagon(const Footprint& f) {
  ScreenPolygon p;
  const std::array<Vec2, 8> v = OctagonVertices(f);
  p.vertices.assign(v.begin(), v.end());
  p.Finalize();
  p.inv_depth = {0, 0, f.inv_depth};
  p.layer = INT_MIN;  // a surface at exactly its depth hides it
  return p;
}

// Whether convex polygon `p` may reach the disc of radius `r` about (x, y): no edge has the whole
// disc outside it. (Conservative near the polygon's corners, where the coverage decides.)
bool ReachesDisc(const ScreenPolygon& p, double x, double y, double r) {
  for (size_t i = 0; i < p.vertices.size(); ++i) {
    const ScreenLinear e = p.Edge(i);
    const double v = e.At(x, y);
    if (v < 0 && v * v > r * r * (e.a * e.a + e.b * e.b)) return false;
  }
  return true;
}

// The polygon's largest inverse depth (its nearest point: a vertex, the depth being linear).
double NearestInvDepth(const ScreenPolygon& p) {
  double w = -INFINITY;
  for (const Vec2& v : p.vertices) w = std::max(w, p.inv_depth.At(v.x, v.y));
  return w;
}

class LightProjector {
 public:
  LightProjector(const Scene& scene, const Camera& camera, const FrameGeometry& geometry,
                 const RenderSettings& settings)
      : scene_(scene),
        camera_(camera),
        geo_(geometry),
        settings_(settings),
        to_camera_(camera.Orientation().Transposed()),
        sx_((geometry.frustum.right - geometry.frustum.left) / geometry.width),
        sy_((geometry.frustum.top - geometry.frustum.bottom) / geometry.height),
        placements_(scene.objects.size()) {
    // Where the objects carrying lights stand this frame, once each, before the lights are
    // projected on several threads.
    std::vector<bool> done(scene.objects.size(), false);
    for (const PointLight& light : scene.lights.lights)
      if (light.object >= 0 && !done[light.object]) {
        done[light.object] = true;
        placements_[light.object] = Place(scene.objects[light.object]);
      }
  }

  // The footprints of light `index` (its own, and its halo in fog), appended to `out`.
  void Project(size_t index, std::vector<Footprint>& out) const {
    const PointLight& light = scene_.lights.lights[index];
    Vec3 world = light.position;
    const Mat3* rotation = nullptr;
    if (light.object >= 0) {
      const std::optional<Placement>& placed = placements_[light.object];
      if (!placed) return;  // its object is hidden
      world = placed->linear * light.position + placed->translation;
      rotation = &placed->rotation;
    }
    const Vec3 to_light = world - camera_.position;
    const double distance = Length(to_light);
    const Vec3 p = to_camera_ * to_light;
    if (!(-p.z > camera_.near) || (camera_.far > 0 && -p.z > camera_.far)) return;
    const double tx = p.x / -p.z, ty = p.y / -p.z;
    const double x = (tx - geo_.frustum.left) / sx_, y = (geo_.frustum.top - ty) / sy_;
    // Beyond the frame by more than the largest footprint: nothing of it can show.
    constexpr double kReach = kMaxFootprintPx + 2;
    if (x < -kReach || x > geo_.width + kReach || y < -kReach || y > geo_.height + kReach) return;
    Vec3 to_eye = to_light * (-1.0 / distance);
    if (rotation != nullptr) to_eye = rotation->Transposed() * to_eye;  // the lobe's frame
    const double intensity =
        LightIntensityTowards(light, to_eye, settings_.scene_time_s, scene_.lights.groups);
    if (!(intensity > 0)) return;
    // The solid angle of one pixel there, and Allard's law through the fog.
    const double pixel_sr = sx_ * sy_ / std::pow(1 + tx * tx + ty * ty, 1.5);
    const double tau = scene_.fog_density * distance;
    const double transmission = std::exp(-tau);
    const double energy =
        scene_.lights.settings.exposure * intensity / (distance * distance) / pixel_sr;
    const double px_per_radian = 1 / sy_;
    const double min_radius = 0.5 * scene_.lights.settings.min_size_px;
    const double lamp_radius = light.radius_m / distance * px_per_radian;
    auto add = [&](double share, double radius) {
      const double s = energy * share;
      const double lum = s * Luminance(light.color.r, light.color.g, light.color.b);
      if (!(lum > 0)) return;
      double r = std::max({min_radius, lamp_radius, radius});
      if (lum > kBloomEnergy) r = std::max(r, min_radius * std::pow(lum / kBloomEnergy, 0.25));
      r = std::min(r, kMaxFootprintPx);
      // Beyond the frame and its filter margin: nothing of it shows.
      if (x + r < -2 || x - r > geo_.width + 2 || y + r < -2 || y - r > geo_.height + 2) return;
      const double per_px2 = s / (kPi * r * r);
      out.push_back({x, y, r, 1 / -p.z, static_cast<float>(per_px2 * light.color.r),
                     static_cast<float>(per_px2 * light.color.g),
                     static_cast<float>(per_px2 * light.color.b)});
    };
    add(transmission, 0);
    if (tau > 0)
      add((1 - transmission) * kHaloForwardShare,
          std::max(2 * std::max(min_radius, lamp_radius),
                   Radians(kHaloDegPerTau * tau) * px_per_radian));
  }

 private:
  struct Placement {
    Mat3 linear, rotation;
    Vec3 translation;
  };
  // Where `object` stands this frame; none while it is hidden.
  static std::optional<Placement> Place(const SceneObject& object) {
    if (!object.visible) return std::nullopt;
    auto placed = PlacementFromProto(object.transform, object.name);
    if (!placed.ok()) return std::nullopt;
    const v1::Transform& t = object.transform;
    return Placement{placed->linear, YawPitchRoll(t.yaw_deg(), t.pitch_deg(), t.roll_deg()),
                     placed->translation};
  }

  const Scene& scene_;
  const Camera& camera_;
  const FrameGeometry& geo_;
  const RenderSettings& settings_;
  Mat3 to_camera_;
  double sx_, sy_;
  std::vector<std::optional<Placement>> placements_;
};

// What deciding whether a polygon may hide a light reads of it, in one cache line: its box, its
// plane and its nearest inverse depth (-inf for a transparent polygon, which hides nothing). Most
// of the polygons seen near a light are refused on these alone, without reading the polygon.
struct alignas(64) OccluderKey {
  double min_x, min_y, max_x, max_y;
  ScreenLinear inv_depth;
  double nearest;
};

std::vector<OccluderKey> OccluderKeys(const FrameGeometry& geometry) {
  std::vector<OccluderKey> keys(geometry.polygons.size());
  tbb::parallel_for(size_t{0}, keys.size(), [&](size_t i) {
    const ScreenPolygon& p = geometry.polygons[i];
    keys[i] = {p.min_x, p.min_y,     p.max_x,
               p.max_y, p.inv_depth, p.transparent ? -INFINITY : NearestInvDepth(p)};
  });
  return keys;
}

// The polygons of the frame by tile, for the lights whose cells the raster pass did not record
// (more polygons seen than a cell keeps, transparent surfaces): each tile's nearest first (by each
// one's nearest inverse depth), so that the search stops at the first polygon behind the light.
struct PolygonTiles {
  static constexpr int kTile = 8;  // a footprint is a few pixels: small tiles, few candidates
  int x0 = 0, y0 = 0;              // the frame region's first pixel, where tile (0, 0) starts
  int columns = 0, rows = 0;
  std::vector<std::vector<int>> tiles;
};

// Fills the tiles of `t` that the boxes of the footprints not `recorded` reach with the polygons
// whose boxes, grown by `margin`, reach them inside `region`, in ascending order (as
// raster/warnock.h's BinPolygons does for every tile); the other tiles stay empty (few
// footprints are not recorded: binning the whole frame would cost more than all their searches).
void BinNearUnrecorded(const std::vector<OccluderKey>& keys,
                       const std::vector<LightFootprint>& footprints,
                       const std::vector<uint8_t>& recorded, const PixelRect& region, double margin,
                       PolygonTiles& t) {
  if (t.columns <= 0 || t.rows <= 0) return;
  const int tile = PolygonTiles::kTile;
  auto column = [&](double x) {
    return std::clamp(static_cast<int>(std::floor((x - t.x0) / tile)), 0, t.columns - 1);
  };
  auto row = [&](double y) {
    return std::clamp(static_cast<int>(std::floor((y - t.y0) / tile)), 0, t.rows - 1);
  };
  std::vector<uint8_t> wanted(t.tiles.size(), 0);
  std::vector<std::pair<int, int>> wanted_list;  // (row, column), row by row
  for (size_t k = 0; k < footprints.size(); ++k) {
    if (recorded[k]) continue;
    const LightFootprint& f = footprints[k];
    const double r = f.radius * kOctagonCircumradius;
    for (int j = row(f.y - r); j <= row(f.y + r); ++j)
      for (int i = column(f.x - r); i <= column(f.x + r); ++i) {
        uint8_t& w = wanted[static_cast<size_t>(j) * t.columns + i];
        if (!w) wanted_list.push_back({j, i});
        w = 1;
      }
  }
  for (size_t index = 0; index < keys.size(); ++index) {
    const OccluderKey& p = keys[index];
    if (p.max_x < region.x0 - margin || p.min_x > region.x1 + margin ||
        p.max_y < region.y0 - margin || p.min_y > region.y1 + margin)
      continue;
    const int j0 = row(p.min_y - margin), j1 = row(p.max_y + margin);
    const int i0 = column(p.min_x - margin), i1 = column(p.max_x + margin);
    if (static_cast<size_t>(j1 - j0 + 1) * (i1 - i0 + 1) > wanted_list.size()) {
      // A polygon over much of the frame (the ground): the wanted tiles it reaches.
      for (const auto& [j, i] : wanted_list)
        if (j >= j0 && j <= j1 && i >= i0 && i <= i1)
          t.tiles[static_cast<size_t>(j) * t.columns + i].push_back(static_cast<int>(index));
      continue;
    }
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) {
        const size_t n = static_cast<size_t>(j) * t.columns + i;
        if (wanted[n]) t.tiles[n].push_back(static_cast<int>(index));
      }
  }
}

// The footprints [first, last) in the order of their places on the screen (by tiles of 32
// pixels, row by row; each tile's in their own order), by a counting sort into `order`.
void OrderByPlace(const std::vector<LightFootprint>& footprints, size_t first, size_t last,
                  const PixelRect& region, std::vector<size_t>& counts,
                  std::vector<uint32_t>& order) {
  constexpr int kPlaceTile = 32;
  const int columns = (region.width() + kPlaceTile - 1) / kPlaceTile;
  const int rows = (region.height() + kPlaceTile - 1) / kPlaceTile;
  auto place = [&](const LightFootprint& f) {
    const int i =
        std::clamp(static_cast<int>(std::floor((f.x - region.x0) / kPlaceTile)), 0, columns - 1);
    const int j =
        std::clamp(static_cast<int>(std::floor((f.y - region.y0) / kPlaceTile)), 0, rows - 1);
    return static_cast<size_t>(j) * columns + i;
  };
  counts.assign(static_cast<size_t>(columns) * rows + 1, 0);
  for (size_t k = first; k < last; ++k) ++counts[place(footprints[k]) + 1];
  for (size_t n = 1; n < counts.size(); ++n) counts[n] += counts[n - 1];
  order.resize(last - first);
  for (size_t k = first; k < last; ++k)
    order[counts[place(footprints[k])]++] = static_cast<uint32_t>(k);
}

// The pixels of `region` a footprint's filter apertures may reach.
PixelRect FootprintPixels(const Footprint& f, const AaFilterShape& shape, const PixelRect& region) {
  const int span = shape.cells_per_axis - 1;
  PixelRect r{std::max(f.CellX0(shape) - span, region.x0),
              std::max(f.CellY0(shape) - span, region.y0), std::min(f.CellX1(shape) + 1, region.x1),
              std::min(f.CellY1(shape) + 1, region.y1)};
  if (r.x1 < r.x0) r.x1 = r.x0;
  if (r.y1 < r.y0) r.y1 = r.y0;
  return r;
}

// How much of a footprint the polygons in front leave.
enum class Shown { kWhole, kPartly, kNone };

// Resolves footprints one at a time against the polygons nearer than each, into the filter
// weights of the pixels they reach (a light's energy per square pixel times its weight is what it
// adds to a pixel).
class Splatter {
 public:
  Splatter(const FrameGeometry& geometry, const std::vector<OccluderKey>& keys,
           const RenderSettings& settings, const VisibleSurfaces* surfaces,
           const PolygonTiles* tiles)
      : geo_(geometry),
        keys_(keys),
        aa_(settings.aa),
        shape_(ShapeOf(settings.aa)),
        surfaces_(surfaces),
        tiles_(tiles) {}

  // Whether the raster pass recorded every cell of the footprint (else its occluders are searched
  // among the polygon tiles).
  static bool Recorded(const Footprint& f, const AaFilterShape& shape,
                       const VisibleSurfaces* surfaces) {
    if (surfaces == nullptr) return false;
    for (int ky = f.CellY0(shape); ky <= f.CellY1(shape); ++ky)
      for (int kx = f.CellX0(shape); kx <= f.CellX1(shape); ++kx)
        if (!surfaces->Holds(kx, ky) || surfaces->count(kx, ky) < 0) return false;
    return true;
  }

  // Adds the footprint's weights to `weights`, the pixels of `pixels` (FootprintPixels) row by row;
  // how much of it shows. `recorded`: Recorded(f, ...).
  Shown Splat(const Footprint& f, bool recorded, const PixelRect& pixels, float* weights) {
    const std::array<Vec2, 8> octagon = OctagonVertices(f);
    Box box{octagon[0].x, octagon[0].y, octagon[0].x, octagon[0].y};
    for (const Vec2& v : octagon) {
      box.x0 = std::min(box.x0, v.x), box.x1 = std::max(box.x1, v.x);
      box.y0 = std::min(box.y0, v.y), box.y1 = std::max(box.y1, v.y);
    }
    found_.clear();
    ++stamp_;
    if (recorded) {
      // The polygons seen in its cells: those hidden there by others nearer still add nothing.
      for (int ky = f.CellY0(shape_); ky <= f.CellY1(shape_); ++ky)
        for (int kx = f.CellX0(shape_); kx <= f.CellX1(shape_); ++kx) {
          surfaces_->ForPolygons(kx, ky, [&](int index) { Found(index); });
        }
    } else {
      SearchTiles(box, f.inv_depth);
    }
    KeepOccluders(f, box);
    // The footprint less the occluders' outlines, in pieces; behind a lattice of outlines, each
    // cell resolved among them instead.
    visible_.Start(octagon);
    const double octagon_area = visible_.Area();
    bool in_pieces = true;
    for (size_t k = 0; k < occluders_.size() && in_pieces && !visible_.empty(); ++k)
      in_pieces = visible_.Subtract(geo_.polygons[occluders_[k]]);
    if (in_pieces && visible_.empty()) return Shown::kNone;
    if (!in_pieces) StackOccluders(f);
    const int span = shape_.cells_per_axis - 1;
    const double offset = shape_.cell_offset;
    // The cells the footprint reaches.
    const int kx0 = static_cast<int>(std::floor(box.x0 - offset));
    const int kx1 = static_cast<int>(std::floor(box.x1 - offset));
    const int ky0 = static_cast<int>(std::floor(box.y0 - offset));
    const int ky1 = static_cast<int>(std::floor(box.y1 - offset));
    const int stride = pixels.width();
    const int columns = kx1 - kx0 + 1;
    // The box filters weigh a cell's area alone: accumulated over the whole grid at once.
    const bool areas_only = in_pieces && !shape_.needs_moments;
    if (areas_only) {
      areas_.resize(static_cast<size_t>(columns) * (ky1 - ky0 + 1));
      visible_.AreasInCells(kx0 + offset, ky0 + offset, columns, ky1 - ky0 + 1, areas_.data());
    }
    row_.resize(columns);
    for (int ky = ky0; ky <= ky1; ++ky) {
      if (in_pieces && !areas_only)
        visible_.InRow(kx0 + offset, ky + offset + 0.5, columns, shape_.needs_moments, row_.data());
      for (int kx = kx0; kx <= kx1; ++kx) {
        const double cx = kx + offset + 0.5, cy = ky + offset + 0.5;
        CellMoments m;
        if (areas_only) {
          m.area = areas_[static_cast<size_t>(ky - ky0) * columns + (kx - kx0)];
        } else if (in_pieces) {
          m = row_[kx - kx0];
        } else {
          pieces_.clear();
          coverage_.Compute(polygons_, candidates_, cx, cy, shape_.needs_moments, pieces_);
          for (const CellPiece& piece : pieces_)
            if (piece.polygon == 0) Accumulate(m, piece.moments);
        }
        if (!(m.area > 0)) continue;
        for (int py = std::max(ky - span, pixels.y0); py <= std::min(ky, pixels.y1 - 1); ++py) {
          float* row = weights + static_cast<size_t>(py - pixels.y0) * stride - pixels.x0;
          for (int px = std::max(kx - span, pixels.x0); px <= std::min(kx, pixels.x1 - 1); ++px)
            row[px] += static_cast<float>(CellWeight(aa_, m, kx - px, ky - py));
        }
      }
    }
    // (Resolved cell by cell, a footprint its occluders reach counts as partly hidden.)
    if (occluders_.empty() || (in_pieces && visible_.Area() >= octagon_area * (1 - 1e-9)))
      return Shown::kWhole;
    return Shown::kPartly;
  }

 private:
  struct Box {
    double x0, y0, x1, y1;
  };

  // Adds polygon `index` to found_ unless it is there already.
  void Found(int index) {
    if (seen_.empty()) seen_.assign(geo_.polygons.size(), 0);
    if (seen_[index] == stamp_) return;
    seen_[index] = stamp_;
    found_.push_back(index);
  }

  // The polygons of the tiles the footprint's box reaches, nearer than the light somewhere, into
  // found_.
  void SearchTiles(const Box& box, double inv_depth) {
    const PolygonTiles& t = *tiles_;
    const int tile = PolygonTiles::kTile;
    const int c0 = std::max(0, static_cast<int>(std::floor((box.x0 - t.x0) / tile)));
    const int c1 = std::min(t.columns - 1, static_cast<int>(std::floor((box.x1 - t.x0) / tile)));
    const int r0 = std::max(0, static_cast<int>(std::floor((box.y0 - t.y0) / tile)));
    const int r1 = std::min(t.rows - 1, static_cast<int>(std::floor((box.y1 - t.y0) / tile)));
    const double nearer = inv_depth * (1 + 1e-9);
    for (int r = r0; r <= r1; ++r)
      for (int c = c0; c <= c1; ++c)
        for (int index : t.tiles[static_cast<size_t>(r) * t.columns + c]) {
          if (!(keys_[index].nearest > nearer)) break;  // the rest are behind it all over
          Found(index);
        }
  }

  // Of the polygons in found_, those that hide the light, into occluders_ (those over the
  // footprint's centre first: they cover most of it, so that the pieces the others cut are few,
  // and one that covers it all leaves none at once). The footprint is the light's image, not a
  // surface, so a polygon hides it or not as a whole, by its outline: when its plane is nearer
  // than the light at the footprint's centre and some of it is nearer than the light. The ground
  // under a runway light does not hide it (the view ray meets the light before the ground), a
  // wall in front of it does, and a far wall whose plane, extended, passes in front does not.
  void KeepOccluders(const Footprint& f, const Box& box) {
    const double nearer = f.inv_depth * (1 + 1e-9);
    occluders_.clear();
    size_t front = 0;
    for (int index : found_) {
      const OccluderKey& k = keys_[index];
      if (k.max_x <= box.x0 || k.min_x >= box.x1 || k.max_y <= box.y0 || k.min_y >= box.y1 ||
          !(k.inv_depth.At(f.x, f.y) > nearer) || !(k.nearest > nearer))
        continue;
      const ScreenPolygon& p = geo_.polygons[index];
      if (!ReachesDisc(p, f.x, f.y, f.radius * kOctagonCircumradius)) continue;
      occluders_.push_back(index);
      if (p.Contains(f.x, f.y)) std::swap(occluders_.back(), occluders_[front++]);
    }
  }

  // The footprint and its occluders for the cell-by-cell resolution: their outlines stacked at
  // distinct depths in front of the light (in any order: what is left of the footprint is outside
  // their union), which the coverage paints one over another from their crossing edges, without
  // pairwise tests (CellCoverage::PaintStacked).
  void StackOccluders(const Footprint& f) {
    polygons_.clear();
    polygons_.push_back(Octagon(f));
    for (size_t k = 0; k < occluders_.size(); ++k) {
      polygons_.push_back(geo_.polygons[occluders_[k]]);
      polygons_.back().inv_depth = {0, 0, f.inv_depth * (2 + 1e-3 * static_cast<double>(k))};
    }
    candidates_.resize(polygons_.size());
    for (size_t k = 0; k < polygons_.size(); ++k) candidates_[k] = static_cast<int>(k);
  }

  const FrameGeometry& geo_;
  const std::vector<OccluderKey>& keys_;
  AntiAliasing aa_;
  AaFilterShape shape_;
  const VisibleSurfaces* surfaces_;
  const PolygonTiles* tiles_;
  VisibleFootprint visible_;
  std::vector<int> found_, occluders_;
  std::vector<CellMoments> row_;
  std::vector<double> areas_;
  // Which polygons found_ holds: seen_[i] == stamp_ (a fresh stamp per footprint).
  std::vector<uint32_t> seen_;
  uint32_t stamp_ = 0;
  // The cell-by-cell resolution.
  CellCoverage coverage_;
  std::vector<ScreenPolygon> polygons_;
  std::vector<int> candidates_;
  std::vector<CellPiece> pieces_;
};

constexpr int kBandRows = 32;
// The pixel weights of one batch of footprints at most (floats): a frame of many large footprints
// is drawn in batches.
constexpr size_t kBatchWeights = size_t{1} << 21;

}  // namespace

std::vector<LightFootprint> ProjectLightPoints(const Scene& scene, const Camera& camera,
                                               const FrameGeometry& geometry,
                                               const RenderSettings& settings) {
  const LightProjector projector(scene, camera, geometry, settings);
  // In chunks on the workers, joined in the lights' order.
  constexpr size_t kChunk = 4096;
  const size_t lights = scene.lights.lights.size();
  std::vector<std::vector<LightFootprint>> chunks((lights + kChunk - 1) / kChunk);
  tbb::parallel_for(size_t{0}, chunks.size(), [&](size_t c) {
    for (size_t i = c * kChunk; i < std::min(lights, (c + 1) * kChunk); ++i)
      projector.Project(i, chunks[c]);
  });
  std::vector<LightFootprint> footprints;
  size_t total = 0;
  for (const auto& chunk : chunks) total += chunk.size();
  footprints.reserve(total);
  for (const auto& chunk : chunks) footprints.insert(footprints.end(), chunk.begin(), chunk.end());
  return footprints;
}

void WantLightCells(const std::vector<LightFootprint>& footprints, const AaFilterShape& shape,
                    VisibleSurfaces& surfaces) {
  for (const LightFootprint& f : footprints)
    surfaces.Want(f.CellX0(shape), f.CellY0(shape), f.CellX1(shape), f.CellY1(shape));
}

absl::Status DrawLightPoints(const FrameGeometry& geometry, const RenderSettings& settings,
                             const PixelRect& region, const std::vector<LightFootprint>& footprints,
                             Image& image, const VisibleSurfaces* surfaces, FrameMemory* memory,
                             LightPassStats* stats, const StopRequested& stop) {
  const Stopwatch timer;
  LightPassStats s;
  if (footprints.empty()) {
    if (stats != nullptr) *stats = s;
    return absl::OkStatus();
  }
  const AaFilterShape shape = ShapeOf(settings.aa);
  const std::vector<OccluderKey> keys = OccluderKeys(geometry);
  size_t held = 0, pass_bytes = HeldBytes(keys);
  // The polygons by tile, nearest first, only when some footprint's cells were not all recorded.
  std::optional<PolygonTiles> tiles;
  std::vector<uint8_t> recorded(footprints.size());
  tbb::parallel_for(tbb::blocked_range<size_t>(0, footprints.size(), 1024),
                    [&](const tbb::blocked_range<size_t>& range) {
                      for (size_t k = range.begin(); k < range.end(); ++k)
                        recorded[k] = Splatter::Recorded(footprints[k], shape, surfaces);
                    });
  if (!std::all_of(recorded.begin(), recorded.end(), [](uint8_t r) { return r != 0; })) {
    PolygonTiles& t = tiles.emplace();
    t.x0 = region.x0, t.y0 = region.y0;
    t.columns = (region.width() + PolygonTiles::kTile - 1) / PolygonTiles::kTile;
    t.rows = (region.height() + PolygonTiles::kTile - 1) / PolygonTiles::kTile;
    t.tiles.resize(static_cast<size_t>(t.columns) * t.rows);
    BinNearUnrecorded(keys, footprints, recorded, region, shape.margin + 1, t);
    pass_bytes += HeldBytes(t.tiles);
    for (const std::vector<int>& tile : t.tiles) pass_bytes += HeldBytes(tile);
    if (memory != nullptr && !memory->Hold(held, pass_bytes)) {
      memory->Refuse("the light points' lists of polygons by tile", pass_bytes);
      return memory->Error();
    }
    tbb::parallel_for(size_t{0}, t.tiles.size(), [&](size_t i) {
      std::sort(t.tiles[i].begin(), t.tiles[i].end(),
                [&](int a, int b) { return keys[a].nearest > keys[b].nearest; });
    });
  }
  // In batches: each footprint resolved on its own (any worker, any order) into its pixels'
  // weights, then the weights added to the image by bands of rows, each band taking the
  // footprints in their order (so the sums do not depend on the workers).
  std::vector<PixelRect> pixels(footprints.size());
  std::vector<size_t> offset(footprints.size() + 1, 0);
  for (size_t k = 0; k < footprints.size(); ++k) {
    pixels[k] = FootprintPixels(footprints[k], shape, region);
    offset[k + 1] = offset[k] + static_cast<size_t>(pixels[k].width()) * pixels[k].height();
  }
  // Resolved in the order of their places on the screen, so that neighbouring footprints, which
  // read the same cells and polygons, follow one another.
  std::vector<size_t> place_counts;
  std::vector<uint32_t> by_place;
  tbb::enumerable_thread_specific<Splatter> splatters(
      [&] { return Splatter(geometry, keys, settings, surfaces, tiles ? &*tiles : nullptr); });
  std::vector<float> weights;
  std::vector<size_t> band_begin, band_fill;
  std::vector<uint32_t> band_footprints;
  std::atomic<size_t> hidden{0}, partly_hidden{0};
  std::atomic<bool> stopped{false};
  for (size_t first = 0; first < footprints.size() && !stopped;) {
    size_t last = first + 1;
    while (last < footprints.size() && offset[last + 1] - offset[first] <= kBatchWeights) ++last;
    weights.assign(offset[last] - offset[first], 0.0f);
    OrderByPlace(footprints, first, last, region, place_counts, by_place);
    if (memory != nullptr && !memory->Hold(held, pass_bytes + HeldBytes(weights))) {
      memory->Refuse("the light points' pixel weights", HeldBytes(weights));
      return memory->Error();
    }
    tbb::parallel_for(tbb::blocked_range<size_t>(0, last - first, 64),
                      [&](const tbb::blocked_range<size_t>& range) {
                        if (stopped.load(std::memory_order_relaxed) || (stop && stop())) {
                          stopped = true;
                          return;
                        }
                        Splatter& splatter = splatters.local();
                        size_t wholly = 0, partly = 0;
                        for (size_t i = range.begin(); i < range.end(); ++i) {
                          const size_t k = by_place[i];
                          switch (splatter.Splat(footprints[k], recorded[k], pixels[k],
                                                 weights.data() + offset[k] - offset[first])) {
                            case Shown::kWhole:
                              break;
                            case Shown::kPartly:
                              ++partly;
                              break;
                            case Shown::kNone:
                              ++wholly;
                              break;
                          }
                        }
                        hidden += wholly;
                        partly_hidden += partly;
                      });
    if (stopped) break;
    // Each band's footprints in their order (a counting sort by band), so that a band passes
    // over only those that reach it.
    const int bands = (region.height() + kBandRows - 1) / kBandRows;
    auto band_of = [&](int y) { return (y - region.y0) / kBandRows; };
    band_begin.assign(static_cast<size_t>(bands) + 1, 0);
    for (size_t k = first; k < last; ++k)
      for (int b = band_of(pixels[k].y0);
           pixels[k].y1 > pixels[k].y0 && b <= band_of(pixels[k].y1 - 1); ++b)
        ++band_begin[b + 1];
    for (int b = 0; b < bands; ++b) band_begin[b + 1] += band_begin[b];
    band_footprints.resize(band_begin[bands]);
    band_fill.assign(band_begin.begin(), band_begin.end() - 1);
    for (size_t k = first; k < last; ++k)
      for (int b = band_of(pixels[k].y0);
           pixels[k].y1 > pixels[k].y0 && b <= band_of(pixels[k].y1 - 1); ++b)
        band_footprints[band_fill[b]++] = static_cast<uint32_t>(k);
    tbb::parallel_for(0, bands, [&](int b) {
      const int row0 = region.y0 + b * kBandRows, row1 = std::min(region.y1, row0 + kBandRows);
      for (size_t i = band_begin[b]; i < band_begin[b + 1]; ++i) {
        const size_t k = band_footprints[i];
        const PixelRect& p = pixels[k];
        const Footprint& f = footprints[k];
        const float* w = weights.data() + offset[k] - offset[first];
        for (int y = std::max(p.y0, row0); y < std::min(p.y1, row1); ++y) {
          const float* row = w + static_cast<size_t>(y - p.y0) * p.width();
          for (int x = p.x0; x < p.x1; ++x) {
            Rgba& pixel = image.at(x - region.x0, y - region.y0);
            const float weight = row[x - p.x0];
            pixel.r += f.r * weight;
            pixel.g += f.g * weight;
            pixel.b += f.b * weight;
          }
        }
      }
    });
    first = last;
  }
  if (memory != nullptr) memory->Hold(held, 0);
  if (stopped) return absl::CancelledError("the frame was stopped while its lights were drawn");
  s.drawn = footprints.size();
  s.hidden = hidden.load();
  s.partly_hidden = partly_hidden.load();
  s.ms = timer.Milliseconds();
  if (stats != nullptr) *stats = s;
  return absl::OkStatus();
}

}  // namespace aperture
