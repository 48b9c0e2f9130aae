#include "render/trace_renderer.h"

#include <tbb/blocked_range2d.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <array>
#include <atomic>
#include <cmath>
#include <limits>
#include <span>

#include "absl/strings/str_cat.h"
#include "base/stopwatch.h"
#include "render/frame_memory.h"
#include "render/sky_backdrop.h"
#include "scene/shading.h"
#include "texture/packed/packed_sampler.h"
#include "texture/summed_area_levels.h"
#include "texture/texture_entries.h"
#include "trace/curved_intersect.h"
#include "trace/texture_mapping.h"

namespace aperture {
namespace {

// Where a ray met a primitive: its texture-plane point (u, v in repeats, seed 003's a, b, c, d;
// for a sphere or cylinder F1's (x', z'), F2 being applied per quad after the seam is unwrapped)
// and its distance from the camera (for fog).
struct Hit {
  int polygon = -1;  // a scene polygon, or polygons + i for scene.curved[i]; -1: nothing
  int part = 0;      // CurvedPart of a curved primitive's hit
  double u = 0, v = 0, distance = 0;
  float nx = 0, ny = 0, nz = 0;  // curved: the unit normal on the camera's side
};

// Corners agree when they lie on one sheet of one primitive.
bool SameSurface(const Hit& a, const Hit& b) { return a.polygon == b.polygon && a.part == b.part; }

// The transparent primitives a ray has passed through (seen through to what lies behind them).
// Past kMaxLayers of them a transparent surface is drawn as if opaque, which bounds a pixel's rays.
struct PassedThrough {
  static constexpr int kMaxLayers = 4;
  int primitives[kMaxLayers];
  int count = 0;
  std::span<const int> span() const { return {primitives, static_cast<size_t>(count)}; }
  PassedThrough With(int primitive) const {
    PassedThrough next = *this;
    next.primitives[next.count++] = primitive;
    return next;
  }
};

// Everything one frame needs, shared read-only by the workers.
class Frame {
 public:
  Frame(const Scene& scene, const RayScene& rays,
        const std::vector<std::unique_ptr<TextureIntegral>>& tables, const Camera& camera,
        const RenderSettings& settings, const TraceOptions& options)
      : scene_(scene),
        rays_(rays),
        tables_(tables),
        camera_(camera),
        settings_(settings),
        options_(options),
        frustum_(ResolveFrustum(camera, settings.width, settings.height)),
        orientation_(camera.Orientation()),
        t_far_(camera.far > 0 ? camera.far : std::numeric_limits<double>::infinity()) {
    // Per polygon: the plane, the texture origin moved to the camera by whole periods (so that
    // precision holds far from the world origin), and the light of its side facing the camera,
    // exactly as raster/projection does.
    for (const ScenePolygon& p : scene.polygons) {
      PolygonFrame f;
      f.normal = p.normal;
      f.height = Dot(p.normal, p.vertices[0] - camera.position);  // plane: dot(n, P - cam) = h
      const TextureOrigin origin = TextureOriginAtCamera(p.mapping, camera.position);
      f.u_cam = origin.u;
      f.v_cam = origin.v;
      const Material& mat = scene.materials[p.material];
      f.light = SurfaceLight(scene, mat, f.height < 0 ? p.normal : -p.normal);
      polygons_.push_back(f);
    }
    for (const CurvedPrimitive& c : scene.curved)
      curved_.push_back({CurvedMapping(c, false), CurvedMapping(c, true)});
  }

  int polygon_count() const { return static_cast<int>(polygons_.size()); }

  // World direction of the ray through screen point (x, y) (pixel corners at integers); its
  // camera-space z is -1, so t along it is the depth.
  Vec3 Direction(double x, double y) const {
    return orientation_ * CameraRay(frustum_, settings_.width, settings_.height, x, y);
  }

  // The ray through (x, y) into `polygon`'s plane (extrapolated beyond the polygon); false when
  // the plane is not ahead of the camera along the ray.
  bool OnPlane(int polygon, double x, double y, Hit* hit) const {
    const PolygonFrame& f = polygons_[polygon];
    const Vec3 d = Direction(x, y);
    const double t = f.height / Dot(f.normal, d);
    if (!(t > 0) || !std::isfinite(t)) return false;
    const TextureMapping& m = scene_.polygons[polygon].mapping;
    hit->polygon = polygon;
    hit->u = f.u_cam + t * Dot(m.su, d);  // seed 003, eq. 1-2: F1 linear, F2 its affine part
    hit->v = f.v_cam + t * Dot(m.sv, d);
    hit->distance = t * Length(d);
    return true;
  }

  // A hit at `point` on curved primitive `index`'s part, with its F1 point and the normal turned
  // to the camera.
  void SetCurvedHit(int index, CurvedPart part, const Vec3& point, Vec3 normal, const Vec3& d,
                    double t, Hit* hit) const {
    const CurvedSlot& slot = curved_[index];
    const bool cap = part == CurvedPart::kBottomCap || part == CurvedPart::kTopCap;
    const TexPoint f1 = F1(cap ? slot.cap : slot.side, point);  // seed 003, eq. 1-2: F1
    if (Dot(normal, d) > 0) normal = -normal;
    hit->polygon = polygon_count() + index;
    hit->part = static_cast<int>(part);
    hit->u = f1.x;
    hit->v = f1.z;
    hit->distance = t * Length(d);
    hit->nx = static_cast<float>(normal.x);
    hit->ny = static_cast<float>(normal.y);
    hit->nz = static_cast<float>(normal.z);
  }

  // The corner ray through (x, y): Embree finds the primitive, the hit point is then recomputed
  // in double on its plane, or by the exact sphere / cylinder intersection from the camera.
  // `point` (optional) receives a curved hit's world point.
  Hit Trace(double x, double y, Vec3* point = nullptr, const PassedThrough& passed = {}) const {
    Hit hit;
    const Vec3 d = Direction(x, y);
    const int primitive = rays_.Intersect(camera_.position, d, camera_.near, t_far_, passed.span());
    if (primitive < 0) return hit;
    if (primitive < polygon_count()) {
      if (!OnPlane(primitive, x, y, &hit)) hit.polygon = -1;
      return hit;
    }
    const int index = primitive - polygon_count();
    const auto c = IntersectCurved(scene_.curved[index], camera_.position, d, camera_.near, t_far_);
    if (!c) return hit;  // a grazing ray Embree's float test kept
    SetCurvedHit(index, c->part, c->point, c->normal, d, c->t, &hit);
    if (point != nullptr) *point = c->point;
    return hit;
  }

  // The ray through (x, y) onto the tangent plane of a curved hit (`centre`, at `point`): the
  // deepest subdivision's stand-in for the surface where corners miss it.
  bool OnTangentPlane(const Hit& centre, const Vec3& point, double x, double y, Hit* hit) const {
    const Vec3 d = Direction(x, y);
    const Vec3 n{centre.nx, centre.ny, centre.nz};
    const double t = Dot(n, point - camera_.position) / Dot(n, d);
    if (!(t > 0) || !std::isfinite(t)) return false;
    SetCurvedHit(centre.polygon - polygon_count(), static_cast<CurvedPart>(centre.part),
                 camera_.position + d * t, n, d, t, hit);
    return true;
  }

  Rgba Sky() const { return FrameSky(scene_, settings_); }

  // Lambert sun plus ambient for the normal `n` on the camera's side.
  Rgba Light(const Material& mat, const Vec3& n) const { return SurfaceLight(scene_, mat, n); }

  // Primitive `polygon` (a polygon or a curved one) over the quad of its four corner hits (a, b,
  // c, d around the pixel, all on one surface).
  Rgba ShadeQuad(int polygon, const std::array<Hit, 4>& c, ProjectionIntegrator* integrator,
                 FragmentStats* stats) const {
    const bool curved = polygon >= polygon_count();
    const int material = curved ? scene_.curved[polygon - polygon_count()].material
                                : scene_.polygons[polygon].material;
    const Material& mat = scene_.materials[material];
    std::array<TexPoint, 4> quad{
        {{c[0].u, c[0].v}, {c[1].u, c[1].v}, {c[2].u, c[2].v}, {c[3].u, c[3].v}}};
    Rgba light;
    if (curved) {
      const CurvedSlot& slot = curved_[polygon - polygon_count()];
      const auto part = static_cast<CurvedPart>(c[0].part);
      const bool cap = part == CurvedPart::kBottomCap || part == CurvedPart::kTopCap;
      quad = UnwrapAndTransform(cap ? slot.cap : slot.side, quad);  // seed 003, eq. 2: F2
      Vec3 n;
      for (const Hit& h : c) n = n + Vec3{h.nx, h.ny, h.nz};
      light = Light(mat, Normalize(n));
    } else {
      light = polygons_[polygon].light;
    }
    Rgba colour = mat.base_color;
    if (mat.texture >= 0) {
      // seed 003: the quad abcd, its fragments and their integrals (eq. 3-4), from the
      // summed-area table or the packed texture's runs (TracedScene::Build made one for every
      // texture a material uses).
      const TextureIntegral& integral = *tables_[mat.texture];
      Rgba texture = integrator->Color(quad, integral, stats);
      if (integral.channels() < 4) texture.a = 1;
      if (scene_.textures[mat.texture]->has_alpha) {  // premultiplied texels (SceneTexture)
        const float k = texture.a > 0 ? 1.0f / texture.a : 0.0f;
        texture.r *= k, texture.g *= k, texture.b *= k;
      }
      colour = colour * texture;
    }
    const float alpha = mat.ShadedAlpha(colour.a);
    colour = colour * light;
    colour = Fogged(scene_, colour,
                    0.25 * (c[0].distance + c[1].distance + c[2].distance + c[3].distance));
    colour.a = alpha;
    return colour;
  }

  struct Local {
    explicit Local(const FragmentOptions& o) : integrator(o) {}
    ProjectionIntegrator integrator;
    FragmentStats stats;
    size_t extra_rays = 0, subdivided = 0;
  };

  // Primitive `polygon` over the square's quad `c`, composited over what lies behind it when it
  // is transparent: its colour weighted by its alpha (over the pixel, like its colour), plus the
  // square traced again past it weighted by 1 - alpha (the same compositing as the raster's).
  Rgba ShadeLayer(int polygon, const std::array<Hit, 4>& c, double x, double y, double size,
                  int depth, Local* local, const PassedThrough& passed) const {
    Rgba colour = ShadeQuad(polygon, c, &local->integrator, &local->stats);
    const float alpha = colour.a;
    if (alpha >= 1.0f || passed.count == PassedThrough::kMaxLayers) {
      colour.a = 1.0f;
      return colour;
    }
    const PassedThrough next = passed.With(polygon);
    const double cx[4] = {0, 1, 1, 0}, cy[4] = {0, 0, 1, 1};
    std::array<Hit, 4> behind;
    for (int k = 0; k < 4; ++k)
      behind[k] = Trace(x + cx[k] * size, y + cy[k] * size, nullptr, next);
    local->extra_rays += 4;
    const Rgba back = ShadeSquare(x, y, size, behind, depth, local, next);
    if (alpha <= 0.0f) return back;
    const float keep = 1.0f - alpha;
    return {alpha * colour.r + keep * back.r, alpha * colour.g + keep * back.g,
            alpha * colour.b + keep * back.b, alpha + keep * back.a};
  }

  // Corners on a curved surface whose normals spread by more than about 2 degrees: F1 bends the
  // pixel's projection, so the straight quad abcd through the corners' texture points would be a
  // poor stand-in for it (most of all near a sphere's limb), and the pixel is subdivided like one
  // whose corners disagree. On the test sphere (48 pixels) 8 degrees gave 38.9 dB against the
  // 64 x 64-sample reference, 2 degrees 52.9 dB, for about 1.7x the time of the curved pixels.
  static bool Bent(const std::array<Hit, 4>& c) {
    if (c[0].nx == 0 && c[0].ny == 0 && c[0].nz == 0) return false;  // a polygon or the sky
    for (int k = 1; k < 4; ++k)
      if (c[0].nx * c[k].nx + c[0].ny * c[k].ny + c[0].nz * c[k].nz < kBentCosine) return true;
    return false;
  }
  static constexpr float kBentCosine = 0.99939f;

  // The square (x, y) .. (x + size, y + size) of the screen with corner hits c (a, b, c, d:
  // top-left, top-right, bottom-right, bottom-left).
  // `passed`: the transparent primitives the rays see through (ShadeLayer).
  Rgba ShadeSquare(double x, double y, double size, const std::array<Hit, 4>& c, int depth,
                   Local* local, const PassedThrough& passed = {}) const {
    const int p = c[0].polygon;
    if (SameSurface(c[0], c[1]) && SameSurface(c[0], c[2]) && SameSurface(c[0], c[3]) &&
        (depth >= options_.max_depth || !Bent(c)))
      return p < 0 ? Sky() : ShadeLayer(p, c, x, y, size, depth, local, passed);
    if (depth >= options_.max_depth) {
      // The deepest level: the primitive the centre ray meets, over the square's corners
      // projected on its plane (a curved primitive: its tangent plane at the centre hit).
      Vec3 point;
      const Hit centre = Trace(x + 0.5 * size, y + 0.5 * size, &point, passed);
      ++local->extra_rays;
      if (centre.polygon < 0) return Sky();
      const bool curved = centre.polygon >= polygon_count();
      std::array<Hit, 4> q;
      const double cx[4] = {0, 1, 1, 0}, cy[4] = {0, 0, 1, 1};
      for (int k = 0; k < 4; ++k) {
        const double qx = x + cx[k] * size, qy = y + cy[k] * size;
        const bool ok = curved ? OnTangentPlane(centre, point, qx, qy, &q[k])
                               : OnPlane(centre.polygon, qx, qy, &q[k]);
        if (!ok) q[k] = centre;
      }
      return ShadeLayer(centre.polygon, q, x, y, size, depth, local, passed);
    }
    // Five more corner rays split the square into four; each quarter weighs 1/4.
    const double h = 0.5 * size;
    const Hit top = Trace(x + h, y, nullptr, passed),
              right = Trace(x + size, y + h, nullptr, passed),
              bottom = Trace(x + h, y + size, nullptr, passed),
              left = Trace(x, y + h, nullptr, passed), mid = Trace(x + h, y + h, nullptr, passed);
    local->extra_rays += 5;
    const Rgba q0 = ShadeSquare(x, y, h, {c[0], top, mid, left}, depth + 1, local, passed);
    const Rgba q1 = ShadeSquare(x + h, y, h, {top, c[1], right, mid}, depth + 1, local, passed);
    const Rgba q2 =
        ShadeSquare(x + h, y + h, h, {mid, right, c[2], bottom}, depth + 1, local, passed);
    const Rgba q3 = ShadeSquare(x, y + h, h, {left, mid, bottom, c[3]}, depth + 1, local, passed);
    return (q0 + q1 + q2 + q3) * 0.25f;
  }

 private:
  struct PolygonFrame {
    Vec3 normal;
    double height = 0;
    double u_cam = 0, v_cam = 0;
    Rgba light;
  };
  struct CurvedSlot {
    PrimitiveMapping side, cap;  // F1 and F2 of the surface and of the caps
  };
  const Scene& scene_;
  const RayScene& rays_;
  const std::vector<std::unique_ptr<TextureIntegral>>& tables_;
  const Camera& camera_;
  const RenderSettings& settings_;
  const TraceOptions& options_;
  FrustumTangents frustum_;
  Mat3 orientation_;
  double t_far_;
  std::vector<PolygonFrame> polygons_;
  std::vector<CurvedSlot> curved_;
};

}  // namespace

absl::Status ValidateTraceOptions(const TraceOptions& options) {
  if (!(options.fragments.delta > 0) || !std::isfinite(options.fragments.delta))
    return absl::InvalidArgumentError("delta must be a positive number");
  if (options.max_depth < 0 || options.max_depth > 8)
    return absl::InvalidArgumentError("max_depth must be in [0, 8]");
  return absl::OkStatus();
}

absl::StatusOr<std::unique_ptr<TracedScene>> TracedScene::Build(
    const Scene& scene, std::shared_ptr<const SharedStore> store, const StopRequested& stop,
    uint64_t memory_budget) {
  if (!scene.lights.lights.empty())
    return absl::InvalidArgumentError(absl::StrCat(
        "the scene has ", scene.lights.lights.size(),
        " light point(s), which only the raster mode draws (aperture-render --mode raster; "
        "options.mode RENDER_MODE_RASTER in a request)"));
  // A summed-area table per raster texture that some material uses (RGB, or RGBA when the
  // texture has any alpha below 1).
  std::vector<bool> used(scene.textures.size(), false);
  for (const Material& m : scene.materials)
    if (m.texture >= 0) used[m.texture] = true;
  std::vector<int> channels(scene.textures.size(), 0);
  uint64_t in_memory = 0;
  for (size_t i = 0; i < scene.textures.size(); ++i) {
    const SceneTexture& t = *scene.textures[i];
    if (!used[i] || t.pyramid == nullptr || t.pyramid->levels() == 0) continue;
    bool alpha = false;
    for (const Rgba& texel : t.pyramid->level(0).texels()) alpha = alpha || texel.a < 1.0f;
    channels[i] = alpha ? 4 : 3;
    if (!store) in_memory += SummedAreaLevelsBytes(*t.pyramid, channels[i]);
  }
  if (!store && memory_budget > 0 && in_memory > memory_budget)
    return absl::ResourceExhaustedError(absl::StrCat(
        "the scene's summed-area tables (", in_memory >> 20,
        " MiB, built in memory: no texture store) do not fit in the budget of ",
        memory_budget >> 20, " MiB for what the server holds in memory (--max-store-mb)"));
  std::unique_ptr<TracedScene> ts(new TracedScene(scene));
  auto rays = RayScene::Build(scene);
  if (!rays.ok()) return rays.status();
  ts->rays_ = std::move(*rays);
  ts->tables_.resize(scene.textures.size());
  for (size_t i = 0; i < scene.textures.size(); ++i) {
    const SceneTexture& t = *scene.textures[i];
    if (channels[i] == 0) continue;
    if (stop && stop())
      return absl::CancelledError("the summed-area tables were stopped part-built");
    const Image& base = t.pyramid->level(0);
    if (!store) {
      for (auto& table : BuildSummedAreaLevels(*t.pyramid, channels[i]))
        ts->tables_[i].push_back(std::move(table));
      continue;
    }
    auto entry = GetOrBuildSummedAreaTables(*store, *t.pyramid, channels[i]);
    auto views = entry.ok() ? ViewSummedAreaLevels((*entry)->payload()) : entry.status();
    if (!views.ok())
      return absl::Status(views.status().code(),
                          absl::StrCat("summed-area tables of texture '", t.id, "' (", base.width(),
                                       " x ", base.height(), " texels, ", channels[i],
                                       " channels): ", views.status().message()));
    ts->entries_.push_back(*std::move(entry));
    for (auto& table : *views) ts->tables_[i].push_back(std::move(table));
  }
  // What the fragments integrate: the tables, and packed vector textures' runs in place.
  ts->integrals_.resize(scene.textures.size());
  for (size_t i = 0; i < scene.textures.size(); ++i) {
    if (!ts->tables_[i].empty()) {
      std::vector<const SummedAreaTable*> levels;
      for (const auto& table : ts->tables_[i]) levels.push_back(table.get());
      ts->integrals_[i] = std::make_unique<TableIntegral>(std::move(levels));
    } else if (const auto* p = dynamic_cast<const packed::PackedTextureSampler*>(
                   scene.textures[i]->packed_area.get());
               used[i] && p != nullptr) {
      ts->integrals_[i] =
          std::make_unique<PackedIntegral>(p->area(), static_cast<int>(p->texture().width()),
                                           static_cast<int>(p->texture().height()));
    }
    if (used[i] && ts->integrals_[i] == nullptr)
      return absl::InternalError(absl::StrCat("texture '", scene.textures[i]->id,
                                              "' has neither texels nor packed runs to integrate"));
  }
  return ts;
}

absl::StatusOr<RenderedFrame> TracedScene::Render(const Camera& camera,
                                                  const RenderSettings& settings,
                                                  const TraceOptions& options, TraceStats* stats,
                                                  const StopRequested& stop) const {
  if (auto s = ValidateRenderSettings(settings); !s.ok()) return s;
  if (auto s = ValidateCamera(camera); !s.ok()) return s;
  if (auto s = ValidateTraceOptions(options); !s.ok()) return s;
  // The region's pixels, traced through the frame's own corners: a frame split into regions is
  // pixel-identical to the whole one (shared corners are traced by both neighbours).
  const PixelRect region = settings.region.pixels() > 0
                               ? settings.region
                               : PixelRect{0, 0, settings.width, settings.height};
  const int w = region.width(), h = region.height(), x0 = region.x0, y0 = region.y0;
  // The image and its corner rays are what grows with the frame (the per-thread fragments are
  // bounded by their work cap), weighed against its budget before they are made.
  FrameMemory memory(settings.max_frame_bytes);
  const size_t frame_bytes = static_cast<size_t>(w) * h * sizeof(Rgba) +
                             static_cast<size_t>(w + 1) * (h + 1) * sizeof(Hit);
  if (frame_bytes > memory.Room()) {
    memory.Refuse("the image and its corner rays", frame_bytes);
    return memory.Error();
  }
  const Frame frame(scene_, *rays_, integrals_, camera, settings, options);
  RenderedFrame out;
  out.region = region;
  out.image = Image::Uninitialized(w, h);
  std::vector<Hit> corners(static_cast<size_t>(w + 1) * (h + 1));
  std::atomic<bool> stopped{false};
  auto stopping = [&] {
    if (!stopped.load(std::memory_order_relaxed) && stop && stop()) stopped = true;
    return stopped.load(std::memory_order_relaxed);
  };
  tbb::enumerable_thread_specific<Frame::Local> locals(options.fragments);
  TraceStats s;

  auto run = [&] {
    out.stats.concurrency = tbb::this_task_arena::max_concurrency();
    // The (W + 1) x (H + 1) corner rays, on tiles.
    Stopwatch timer;
    tbb::parallel_for(tbb::blocked_range2d<int>(0, h + 1, 16, 0, w + 1, 64),
                      [&](const tbb::blocked_range2d<int>& r) {
                        if (stopping()) return;
                        for (int y = r.rows().begin(); y < r.rows().end(); ++y)
                          for (int x = r.cols().begin(); x < r.cols().end(); ++x)
                            corners[static_cast<size_t>(y) * (w + 1) + x] =
                                frame.Trace(x0 + x, y0 + y);
                      });
    s.corner_ms = timer.Milliseconds();
    // Pixels, on tiles: each reads its four shared corners.
    timer.Restart();
    tbb::parallel_for(
        tbb::blocked_range2d<int>(0, h, 16, 0, w, 64), [&](const tbb::blocked_range2d<int>& r) {
          if (stopping()) return;
          Frame::Local& local = locals.local();
          for (int y = r.rows().begin(); y < r.rows().end(); ++y)
            for (int x = r.cols().begin(); x < r.cols().end(); ++x) {
              const size_t i = static_cast<size_t>(y) * (w + 1) + x;
              const std::array<Hit, 4> c{corners[i], corners[i + 1], corners[i + w + 2],
                                         corners[i + w + 1]};
              const bool agree =
                  SameSurface(c[0], c[1]) && SameSurface(c[0], c[2]) && SameSurface(c[0], c[3]);
              if (!agree) ++local.subdivided;
              out.image.at(x, y) = frame.ShadeSquare(x0 + x, y0 + y, 1.0, c, 0, &local);
            }
        });
    if (!stopping() && SkyByDirection(scene_, settings))
      CompositeSky(scene_.sky_dome, camera, settings.width, settings.height, region, out.image);
    s.shade_ms = timer.Milliseconds();
  };
  try {
    if (settings.threads > 0) {
      tbb::task_arena arena(settings.threads);
      arena.execute(run);
    } else {
      run();
    }
  } catch (const std::bad_alloc&) {
    return absl::ResourceExhaustedError(
        "the process ran out of memory while tracing the frame (its budget, --max-frame-mb, is "
        "larger than what the machine has free)");
  }
  if (stopped) return absl::CancelledError("the frame was stopped");
  s.corner_rays = corners.size();
  for (const Frame::Local& l : locals) {
    s.extra_rays += l.extra_rays;
    s.subdivided_pixels += l.subdivided;
    s.fragments.Add(l.stats);
  }
  out.stats.setup_ms = s.corner_ms;
  out.stats.peak_memory_bytes = frame_bytes;
  out.stats.raster_ms = s.shade_ms;
  if (stats != nullptr) *stats = s;
  return out;
}

}  // namespace aperture
