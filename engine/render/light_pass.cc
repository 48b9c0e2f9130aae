#include "render/light_pass.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <climits>
#include <cmath>
#include <optional>
#include <vector>

#include "base/stopwatch.h"
#include "raster/cell_coverage.h"
#include "raster/polygon_moments.h"
#include "raster/warnock.h"
#include "scene/object_placement.h"
#include "scene/triangulate.h"

namespace aperture {
namespace {

// A footprint on the screen: a disc of `radius` pixels (drawn as the regular octagon of its
// area) at the light's depth, carrying `r, g, b` pixel values per square pixel.
struct Footprint {
  double x, y, radius;
  double inv_depth;  // 1 / view depth, as ScreenPolygon::inv_depth
  Vec3 world;        // the light's position (the surfaces it stands on do not hide it)
  float r, g, b;
};

// Rec. 709 luminance of a colour.
double Luminance(double r, double g, double b) { return 0.2126 * r + 0.7152 * g + 0.0722 * b; }

// The octagon whose area is the disc's, edges along the axes and diagonals, counter-clockwise on
// the screen (y down), as ScreenPolygon keeps its vertices.
ScreenPolygon Octagon(const Footprint& f) {
  // A regular octagon of circumradius R has area 2 sqrt(2) R^2.
  const double circumradius = f.radius * std::sqrt(kPi / (2 * std::sqrt(2.0)));
  ScreenPolygon p;
  for (int k = 0; k < 8; ++k) {
    const double a = -(k + 0.5) * kPi / 4;  // clockwise in y-up terms: counter-clockwise y down
    p.vertices.push_back({f.x + circumradius * std::cos(a), f.y + circumradius * std::sin(a)});
  }
  if (SignedArea(p.vertices) < 0) std::reverse(p.vertices.begin(), p.vertices.end());
  p.Finalize();
  p.inv_depth = {0, 0, f.inv_depth};
  p.layer = INT_MIN;  // a surface at exactly its depth hides it
  return p;
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
        placements_(scene.objects.size()) {}

  // The footprints of light `index` (its own, and its halo in fog), appended to `out`.
  void Project(size_t index, std::vector<Footprint>& out) {
    const PointLight& light = scene_.lights.lights[index];
    Vec3 world = light.position;
    const Mat3* rotation = nullptr;
    if (light.object >= 0) {
      const Placement* placed = PlacementOf(light.object);
      if (placed == nullptr) return;  // its object is hidden
      world = placed->linear * light.position + placed->translation;
      rotation = &placed->rotation;
    }
    const Vec3 to_light = world - camera_.position;
    const double distance = Length(to_light);
    const Vec3 p = to_camera_ * to_light;
    if (!(-p.z > camera_.near) || (camera_.far > 0 && -p.z > camera_.far)) return;
    Vec3 to_eye = to_light * (-1.0 / distance);
    if (rotation != nullptr) to_eye = rotation->Transposed() * to_eye;  // the lobe's frame
    const double intensity =
        LightIntensityTowards(light, to_eye, settings_.scene_time_s, scene_.lights.groups);
    if (!(intensity > 0)) return;
    const double tx = p.x / -p.z, ty = p.y / -p.z;
    const double x = (tx - geo_.frustum.left) / sx_, y = (geo_.frustum.top - ty) / sy_;
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
      out.push_back({x, y, r, 1 / -p.z, world, static_cast<float>(per_px2 * light.color.r),
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
  // Where named object `index` stands this frame; null while it is hidden.
  const Placement* PlacementOf(int index) {
    std::optional<std::optional<Placement>>& slot = placements_[index];
    if (!slot) {
      const SceneObject& object = scene_.objects[index];
      slot.emplace();
      if (object.visible) {
        auto placed = PlacementFromProto(object.transform, object.name);
        if (placed.ok()) {
          const v1::Transform& t = object.transform;
          *slot = Placement{placed->linear, YawPitchRoll(t.yaw_deg(), t.pitch_deg(), t.roll_deg()),
                            placed->translation};
        }
      }
    }
    return *slot ? &**slot : nullptr;
  }

  const Scene& scene_;
  const Camera& camera_;
  const FrameGeometry& geo_;
  const RenderSettings& settings_;
  Mat3 to_camera_;
  double sx_, sy_;
  std::vector<std::optional<std::optional<Placement>>> placements_;
};

// Splats footprints into the image, rows [row0, row1) of the frame only (so bands of rows can be
// drawn at once), resolving each footprint's cells against the polygons nearer than it.
class Splatter {
 public:
  Splatter(const Scene& scene, const FrameGeometry& geometry, const RenderSettings& settings,
           const PixelRect& region, const std::vector<std::vector<int>>& tiles, int columns,
           int tile, const std::vector<double>& nearest, Image& image)
      : scene_(scene),
        geo_(geometry),
        aa_(settings.aa),
        shape_(ShapeOf(settings.aa)),
        region_(region),
        tiles_(tiles),
        columns_(columns),
        tile_(tile),
        nearest_(nearest),
        image_(image) {}

  // Whether polygons were nearer than the footprint over part of it.
  bool Splat(const Footprint& f, int row0, int row1) {
    polygons_.clear();
    polygons_.push_back(Octagon(f));
    const ScreenPolygon& fp = polygons_[0];
    GatherOccluders(f, fp);
    candidates_.resize(polygons_.size());
    for (size_t k = 0; k < polygons_.size(); ++k) candidates_[k] = static_cast<int>(k);
    const int span = shape_.cells_per_axis - 1;
    const double offset = shape_.cell_offset;
    // The cells the footprint reaches whose pixels lie in the rows drawn.
    const int kx0 = static_cast<int>(std::floor(fp.min_x - offset));
    const int kx1 = static_cast<int>(std::floor(fp.max_x - offset));
    const int ky0 = std::max(static_cast<int>(std::floor(fp.min_y - offset)), row0);
    const int ky1 = std::min(static_cast<int>(std::floor(fp.max_y - offset)), row1 - 1 + span);
    for (int ky = ky0; ky <= ky1; ++ky) {
      for (int kx = kx0; kx <= kx1; ++kx) {
        pieces_.clear();
        coverage_.Compute(polygons_, candidates_, kx + offset + 0.5, ky + offset + 0.5,
                          shape_.needs_moments, pieces_);
        CellMoments m;
        for (const CellPiece& piece : pieces_)
          if (piece.polygon == 0) Accumulate(m, piece.moments);
        if (!(m.area > 0)) continue;
        for (int py = std::max({ky - span, row0, region_.y0});
             py <= std::min({ky, row1 - 1, region_.y1 - 1}); ++py) {
          for (int px = std::max(kx - span, region_.x0); px <= std::min(kx, region_.x1 - 1); ++px) {
            const double w = CellWeight(aa_, m, kx - px, ky - py);
            Rgba& pixel = image_.at(px - region_.x0, py - region_.y0);
            pixel.r += static_cast<float>(f.r * w);
            pixel.g += static_cast<float>(f.g * w);
            pixel.b += static_cast<float>(f.b * w);
          }
        }
      }
    }
    return polygons_.size() > 1;
  }

 private:
  // The opaque polygons that may be nearer than the footprint over part of it, but for those
  // whose plane the light stands on, appended to polygons_ after the footprint.
  void GatherOccluders(const Footprint& f, const ScreenPolygon& fp) {
    found_.clear();
    const int c0 = std::max(0, static_cast<int>(std::floor((fp.min_x - region_.x0) / tile_)));
    const int c1 =
        std::min(columns_ - 1, static_cast<int>(std::floor((fp.max_x - region_.x0) / tile_)));
    const int rows = columns_ > 0 ? static_cast<int>(tiles_.size()) / columns_ : 0;
    const int r0 = std::max(0, static_cast<int>(std::floor((fp.min_y - region_.y0) / tile_)));
    const int r1 =
        std::min(rows - 1, static_cast<int>(std::floor((fp.max_y - region_.y0) / tile_)));
    const double nearer = f.inv_depth * (1 + 1e-9);
    for (int r = r0; r <= r1; ++r) {
      for (int c = c0; c <= c1; ++c) {
        for (int index : tiles_[static_cast<size_t>(r) * columns_ + c]) {
          if (!(nearest_[index] > nearer)) continue;  // behind the light all over
          const ScreenPolygon& p = geo_.polygons[index];
          if (p.transparent || p.max_x <= fp.min_x || p.min_x >= fp.max_x || p.max_y <= fp.min_y ||
              p.min_y >= fp.max_y)
            continue;
          const ScenePolygon& surface = scene_.polygons[p.scene_polygon];
          if (std::abs(Dot(surface.normal, f.world - surface.vertices[0])) <= kSurfaceOffsetM)
            continue;  // the light stands on it
          found_.push_back(index);
        }
      }
    }
    std::sort(found_.begin(), found_.end());
    found_.erase(std::unique(found_.begin(), found_.end()), found_.end());
    for (int index : found_) polygons_.push_back(geo_.polygons[index]);
  }

  const Scene& scene_;
  const FrameGeometry& geo_;
  AntiAliasing aa_;
  AaFilterShape shape_;
  PixelRect region_;
  const std::vector<std::vector<int>>& tiles_;
  int columns_, tile_;
  const std::vector<double>& nearest_;
  Image& image_;
  CellCoverage coverage_;
  std::vector<ScreenPolygon> polygons_;
  std::vector<int> candidates_, found_;
  std::vector<CellPiece> pieces_;
};

constexpr int kBandRows = 32;
constexpr int kTile = 32;

}  // namespace

absl::Status DrawLightPoints(const Scene& scene, const Camera& camera,
                             const FrameGeometry& geometry, const RenderSettings& settings,
                             const PixelRect& region, Image& image, LightPassStats* stats,
                             const StopRequested& stop) {
  const Stopwatch timer;
  LightPassStats s;
  if (scene.lights.lights.empty()) {
    if (stats != nullptr) *stats = s;
    return absl::OkStatus();
  }
  std::vector<Footprint> footprints;
  {
    LightProjector projector(scene, camera, geometry, settings);
    for (size_t i = 0; i < scene.lights.lights.size(); ++i) projector.Project(i, footprints);
  }
  // The rows each footprint's pixels reach, by bands of rows.
  const AaFilterShape shape = ShapeOf(settings.aa);
  const int bands = (region.height() + kBandRows - 1) / kBandRows;
  std::vector<std::vector<int>> band_lights(std::max(bands, 0));
  for (size_t k = 0; k < footprints.size(); ++k) {
    const Footprint& f = footprints[k];
    const int first = static_cast<int>(std::floor(f.y - f.radius * 1.06 - shape.margin)) - 1;
    const int last = static_cast<int>(std::floor(f.y + f.radius * 1.06 + shape.margin)) + 1;
    const int b0 = std::max(0, (first - region.y0) / kBandRows);
    const int b1 = std::min(bands - 1, (last - region.y0) / kBandRows);
    if (last < region.y0 || first >= region.y1) continue;
    for (int b = b0; b <= b1; ++b) band_lights[b].push_back(static_cast<int>(k));
  }
  // Polygons by tile of the region, and each one's nearest inverse depth.
  int columns = 0;
  const std::vector<std::vector<int>> tiles =
      BinPolygons(geometry, shape.margin + 1, region, kTile, &columns);
  std::vector<double> nearest(geometry.polygons.size());
  tbb::parallel_for(size_t{0}, geometry.polygons.size(), [&](size_t i) {
    const ScreenPolygon& p = geometry.polygons[i];
    double w = -INFINITY;
    for (const Vec2& v : p.vertices) w = std::max(w, p.inv_depth.At(v.x, v.y));
    nearest[i] = w;
  });
  std::atomic<size_t> occluded{0};
  std::atomic<bool> stopped{false};
  tbb::parallel_for(0, bands, [&](int b) {
    if (stopped.load(std::memory_order_relaxed) || (stop && stop())) {
      stopped = true;
      return;
    }
    Splatter splatter(scene, geometry, settings, region, tiles, columns, kTile, nearest, image);
    const int row0 = region.y0 + b * kBandRows, row1 = std::min(region.y1, row0 + kBandRows);
    size_t hidden = 0;  // counted in the band that holds the footprint's centre
    for (int k : band_lights[b]) {
      const Footprint& f = footprints[k];
      const bool behind = splatter.Splat(f, row0, row1);
      hidden += behind && f.y >= row0 && f.y < row1;
    }
    occluded += hidden;
  });
  if (stopped) return absl::CancelledError("the frame was stopped while its lights were drawn");
  s.drawn = footprints.size();
  s.occluded = occluded.load();
  s.ms = timer.Milliseconds();
  if (stats != nullptr) *stats = s;
  return absl::OkStatus();
}

}  // namespace aperture
