#include "testing/grazing_plane.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>

#include "texture/reference_sampler.h"

namespace aperture {
namespace {

constexpr double kWorldToRepeats = 0.25;  // u = x / 4, v = z / 4

struct Frame {
  double f, s, c, cx, cy;  // focal length (pixels), sin and cos of the pitch, image centre
  double cos_yaw, sin_yaw;
  // The yaw turns the texture's axes under the camera: (u, v) in the camera's ground frame
  // rotated into the texture's. A rotation: derivatives turn the same way.
  void Turn(double* u, double* v) const {
    const double tu = cos_yaw * *u - sin_yaw * *v, tv = sin_yaw * *u + cos_yaw * *v;
    *u = tu;
    *v = tv;
  }
};

Frame MakeFrame(const GrazingPlaneView& view) {
  const double pitch = view.pitch_deg * M_PI / 180.0, yaw = view.yaw_deg * M_PI / 180.0;
  return {0.5 * view.height / std::tan(0.5 * view.fov_deg * M_PI / 180.0),
          std::sin(pitch),
          std::cos(pitch),
          0.5 * view.width,
          0.5 * view.height,
          std::cos(yaw),
          std::sin(yaw)};
}

// GroundPoint with the view's frame computed once by the caller (its trigonometry would
// dominate the reference's inner loop).
bool GroundPointInFrame(const GrazingPlaneView& view, const Frame& fr, double px, double py,
                        double* u, double* v) {
  // Ray direction: right (1, 0, 0), up (0, cos, -sin), forward (0, -sin, -cos).
  const double dx = (px - fr.cx) / fr.f, dy = -(py - fr.cy) / fr.f;
  const double q = fr.s - dy * fr.c;  // -direction.y: the ray descends when q > 0
  if (q <= 0) return false;
  *u = kWorldToRepeats * dx / q;
  *v = kWorldToRepeats * (-dy * fr.s - fr.c) / q;
  if (view.yaw_deg != 0) fr.Turn(u, v);
  *u += view.origin_u;
  *v += view.origin_v;
  return true;
}

}  // namespace

bool GroundPoint(const GrazingPlaneView& view, double px, double py, double* u, double* v) {
  return GroundPointInFrame(view, MakeFrame(view), px, py, u, v);
}

bool GroundFootprint(const GrazingPlaneView& view, int i, int j, TextureFootprint* f) {
  const Frame fr = MakeFrame(view);
  const double px = i + 0.5, py = j + 0.5;
  const double dx = (px - fr.cx) / fr.f, dy = -(py - fr.cy) / fr.f;
  const double q = fr.s - dy * fr.c;
  if (q <= 0) return false;
  const double nz = -dy * fr.s - fr.c;
  // seed 000, eq. 2 for this plane: U = dx / q, V = nz / q, with dq/dpy = cos / f,
  // d(nz)/dpy = sin / f and dx / dpx = 1 / f.
  const double a = view.aperture * kWorldToRepeats;
  double u = kWorldToRepeats * dx / q, v = kWorldToRepeats * nz / q;
  double dudx = a / (fr.f * q), dvdx = 0;
  double dudy = a * (-dx * fr.c / fr.f) / (q * q),
         dvdy = a * (fr.s * q - nz * fr.c) / (fr.f * q * q);
  if (view.yaw_deg != 0) {
    fr.Turn(&u, &v);
    fr.Turn(&dudx, &dvdx);
    fr.Turn(&dudy, &dvdy);
  }
  u += view.origin_u;
  v += view.origin_v;
  f->u = u - std::floor(u);
  f->v = v - std::floor(v);
  f->dudx = static_cast<float>(dudx);
  f->dvdx = static_cast<float>(dvdx);
  f->dudy = static_cast<float>(dudy);
  f->dvdy = static_cast<float>(dvdy);
  return true;
}

int FirstMeasuredRow(const GrazingPlaneView& view) {
  const Frame fr = MakeFrame(view);
  const double horizon = fr.cy - fr.f * fr.s / fr.c;  // q = 0
  // Row j's 2 x 2 aperture spans [j - 0.5, j + 1.5]: its top must be below the horizon.
  return std::clamp(static_cast<int>(std::floor(horizon + 0.5)) + 1, 0, view.height);
}

Scene GrazingPlaneScene(std::shared_ptr<const SceneTexture> texture) {
  Scene scene;
  scene.name = "grazing-plane";
  scene.textures.push_back(std::move(texture));
  Material m;
  m.id = "ground";
  m.texture = 0;
  m.unlit = true;
  scene.materials.push_back(m);
  ScenePolygon ground;
  const double l = 20000;
  ground.vertices = {{-l, 0, -l}, {-l, 0, l}, {l, 0, l}, {l, 0, -l}};
  ground.normal = {0, 1, 0};
  ground.mapping.su = {0.25, 0, 0};
  ground.mapping.sv = {0, 0, 0.25};
  scene.polygons.push_back(ground);
  scene.ambient = {1, 1, 1, 1};
  scene.sky = {0, 0, 0, 1};
  return scene;
}

Image RenderGroundImage(const GrazingPlaneView& view, const TextureSampler& sampler) {
  Image out(view.width, view.height);
  tbb::parallel_for(0, view.height, [&](int j) {
    TextureFootprint f;
    for (int i = 0; i < view.width; ++i)
      out.at(i, j) = GroundFootprint(view, i, j, &f) ? sampler.Sample(f) : Rgba{0, 0, 0, 1};
  });
  return out;
}

double NanosecondsPerSample(const GrazingPlaneView& view, const TextureSampler& sampler,
                            int rows_step) {
  std::vector<TextureFootprint> footprints;
  for (int j = FirstMeasuredRow(view); j < view.height; j += rows_step) {
    TextureFootprint f;
    for (int i = 0; i < view.width; ++i)
      if (GroundFootprint(view, i, j, &f)) footprints.push_back(f);
  }
  if (footprints.empty()) return 0;
  // Through SampleMany, in batches of about a row, as the renderer calls the samplers. The
  // fastest of three passes: the machine may be shared.
  constexpr size_t kBatch = 256;
  std::vector<Rgba> out(kBatch);
  double best = INFINITY;
  for (int pass = 0; pass < 3; ++pass) {
    float sink = 0;
    const auto start = std::chrono::steady_clock::now();
    for (size_t first = 0; first < footprints.size(); first += kBatch) {
      const int n = static_cast<int>(std::min(kBatch, footprints.size() - first));
      sampler.SampleMany(&footprints[first], out.data(), n);
      for (int i = 0; i < n; ++i) sink += out[i].g;
    }
    const double ns =
        std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - start).count();
    volatile float keep = sink;
    (void)keep;
    best = std::min(best, ns);
  }
  return best / static_cast<double>(footprints.size());
}

Image RenderGroundReference(const GrazingPlaneView& view, const Image& texture, double density,
                            int max_per_side, int min_per_side, int first_row, int end_row) {
  Image out(view.width, view.height);
  const double a = view.aperture, n = texture.width();
  const Frame frame = MakeFrame(view);
  const int end = end_row < 0 ? view.height : std::min(end_row, view.height);
  for (int j = 0; j < view.height; ++j)
    if (j < first_row || j >= end)
      for (int i = 0; i < view.width; ++i) out.at(i, j) = {0, 0, 0, 1};
  tbb::parallel_for(std::max(0, first_row), std::max(0, end), [&](int j) {
    TextureFootprint f;
    for (int i = 0; i < view.width; ++i) {
      if (!GroundFootprint(view, i, j, &f)) {
        out.at(i, j) = {0, 0, 0, 1};
        continue;
      }
      // Strata per side from the texels the aperture spans along each screen axis (the
      // derivative at the aperture's far edge, where the texture is most compressed).
      TextureFootprint far = f;
      if (j > 0)
        GroundFootprint(view, i, std::max(0, j - static_cast<int>(std::ceil(a / 2))), &far);
      auto strata = [&](double du, double dv) {
        return std::clamp(static_cast<int>(std::ceil(std::hypot(du, dv) * n * density)),
                          std::min(min_per_side, max_per_side), max_per_side);
      };
      const int kx = strata(std::max(std::abs(f.dudx), std::abs(far.dudx)),
                            std::max(std::abs(f.dvdx), std::abs(far.dvdx)));
      const int ky = strata(std::max(std::abs(f.dudy), std::abs(far.dudy)),
                            std::max(std::abs(f.dvdy), std::abs(far.dvdy)));
      const uint64_t key = static_cast<uint64_t>(j) * view.width + i;
      double r = 0, g = 0, b = 0;
      int count = 0;
      for (int sy = 0; sy < ky; ++sy) {
        for (int sx = 0; sx < kx; ++sx) {
          const double px = i + 0.5 + a * ((sx + StratumJitter(key, sx, sy, 0)) / kx - 0.5);
          const double py = j + 0.5 + a * ((sy + StratumJitter(key, sx, sy, 1)) / ky - 0.5);
          double u, v;
          if (!GroundPointInFrame(view, frame, px, py, &u, &v)) continue;  // sky: 0
          const Rgba c = BilinearPeriodic(texture, u - std::floor(u), v - std::floor(v));
          r += c.r, g += c.g, b += c.b;
          ++count;
        }
      }
      const double inv = 1.0 / (static_cast<double>(kx) * ky);
      (void)count;
      out.at(i, j) = {static_cast<float>(r * inv), static_cast<float>(g * inv),
                      static_cast<float>(b * inv), 1.0f};
    }
  });
  return out;
}

void MoveForward(GrazingPlaneView* view, double world_units) {
  // Forward is (0, -1) in the camera's ground frame (v = z / 4, looking along -z), turned by the
  // yaw as GroundPoint turns coordinates.
  const double yaw = view->yaw_deg * M_PI / 180.0, step = world_units * kWorldToRepeats;
  view->origin_u += step * std::sin(yaw);
  view->origin_v -= step * std::cos(yaw);
}

namespace {

// The radical inverse of k in base 2 (van der Corput): for the first N = 2^m values of k, every
// multiple of 1 / N once, and so for 3k (3 is odd: k -> 3k is a permutation mod 2^m).
double VanDerCorput(uint32_t k) {
  uint32_t x = 0;
  for (int bit = 0; bit < 32; ++bit, k >>= 1) x = x << 1 | (k & 1);
  return x * 0x1p-32;
}

}  // namespace

GrazingPlaneView ViewAtPosition(const GrazingPlaneView& view, int k) {
  // In texels of a 1024-texel repeat (the benchmark textures'), on three scales:
  //  - the phase within the checkerboard's 128-texel cells, where its edges fall: the van der
  //    Corput sequence of k along U and of 3k along V, so that for 2^m positions both axes meet
  //    the edges at the same 2^m evenly spread phases (a view along U and its mirror along V
  //    score alike), and their sum, the phase that matters looking along a diagonal, takes 3 of
  //    4 strata for four positions (no pairing takes all 4) and 9 of 16 for sixteen;
  //  - the cell of the repeat, 3k and 5k mod 8 (the photos' content);
  //  - the phase within a texel, the R2 sequence's fractions k / g and k / g^2 (g the plastic
  //    number, g^3 = g + 1).
  // (Whole-texel steps of 389 k and 583 k would spread the positions over the repeat but not
  // over a cell along U: 389 = 5 mod 128 puts four positions' edges within 16 texels.)
  constexpr double kG = 1.32471795724474602596;
  const uint32_t i = static_cast<uint32_t>(k);
  GrazingPlaneView moved = view;
  double whole = 0;
  const double u = 128.0 * ((3 * i) % 8 + VanDerCorput(i)) + std::modf(k / kG, &whole);
  const double v = 128.0 * ((5 * i) % 8 + VanDerCorput(3 * i)) + std::modf(k / (kG * kG), &whole);
  moved.origin_u = view.origin_u + std::modf(u / 1024.0, &whole);
  moved.origin_v = view.origin_v + std::modf(v / 1024.0, &whole);
  return moved;
}

YawSpread SpreadAcrossYaws(std::span<const double> yaws, std::span<const double> psnrs) {
  YawSpread out;
  if (psnrs.empty() || yaws.size() != psnrs.size()) return out;
  const auto [lowest, highest] = std::minmax_element(psnrs.begin(), psnrs.end());
  out.spread = *highest - *lowest;
  out.lowest_yaw = yaws[static_cast<size_t>(lowest - psnrs.begin())];
  return out;
}

double PooledPsnr(std::span<const double> psnrs) {
  if (psnrs.empty()) return 0;
  double mse = 0;
  for (double p : psnrs) mse += std::pow(10.0, -p / 10.0);  // 0 for an infinite PSNR
  mse /= static_cast<double>(psnrs.size());
  return mse == 0 ? INFINITY : 10.0 * std::log10(1.0 / mse);
}

double Psnr(const Image& a, const Image& b, int first_row) {
  double sum = 0;
  uint64_t count = 0;
  for (int j = first_row; j < a.height(); ++j)
    for (int i = 0; i < a.width(); ++i) {
      const Rgba &p = a.at(i, j), &q = b.at(i, j);
      sum += double(p.r - q.r) * (p.r - q.r) + double(p.g - q.g) * (p.g - q.g) +
             double(p.b - q.b) * (p.b - q.b);
      count += 3;
    }
  if (count == 0) return 0;
  const double mse = sum / static_cast<double>(count);
  return mse == 0 ? INFINITY : 10.0 * std::log10(1.0 / mse);
}

double MeanAbsoluteChange(const Image& a, const Image& a_prev, const Image* r, const Image* r_prev,
                          int first_row) {
  double sum = 0;
  uint64_t count = 0;
  for (int j = std::max(0, first_row); j < a.height(); ++j)
    for (int i = 0; i < a.width(); ++i) {
      const Rgba &p = a.at(i, j), &q = a_prev.at(i, j);
      double d[3] = {double(p.r) - q.r, double(p.g) - q.g, double(p.b) - q.b};
      if (r != nullptr) {
        const Rgba &s = r->at(i, j), &w = r_prev->at(i, j);
        d[0] -= double(s.r) - w.r, d[1] -= double(s.g) - w.g, d[2] -= double(s.b) - w.b;
      }
      sum += std::abs(d[0]) + std::abs(d[1]) + std::abs(d[2]);
      count += 3;
    }
  return count ? sum / static_cast<double>(count) : 0;
}

std::vector<double> PsnrByRow(const Image& a, const Image& b, int first_row) {
  std::vector<double> rows(a.height(), NAN);
  for (int j = std::max(0, first_row); j < a.height(); ++j) {
    double sum = 0;
    for (int i = 0; i < a.width(); ++i) {
      const Rgba &p = a.at(i, j), &q = b.at(i, j);
      sum += double(p.r - q.r) * (p.r - q.r) + double(p.g - q.g) * (p.g - q.g) +
             double(p.b - q.b) * (p.b - q.b);
    }
    const double mse = sum / (3.0 * a.width());
    rows[j] = mse == 0 ? INFINITY : 10.0 * std::log10(1.0 / mse);
  }
  return rows;
}

double FootprintLength(const GrazingPlaneView& view, int i, int j, int texture_size) {
  TextureFootprint f;
  if (!GroundFootprint(view, i, j, &f)) return 0;
  // The derivatives carry the aperture a: one pixel's steps are 1 / a of them.
  return texture_size / view.aperture *
         std::max(std::hypot(f.dudx, f.dvdx), std::hypot(f.dudy, f.dvdy));
}

double FootprintAngleFromAxis(const GrazingPlaneView& view, int i, int j) {
  TextureFootprint f;
  if (!GroundFootprint(view, i, j, &f)) return 0;
  // The principal axis of X X^T + Y Y^T (X, Y the steps) is at 0.5 atan2(2 M_uv, M_uu - M_vv)
  // to U.
  const double uu = double(f.dudx) * f.dudx + double(f.dudy) * f.dudy;
  const double vv = double(f.dvdx) * f.dvdx + double(f.dvdy) * f.dvdy;
  const double uv = double(f.dudx) * f.dvdx + double(f.dudy) * f.dvdy;
  const double to_u = std::abs(0.5 * std::atan2(2 * uv, uu - vv)) * 180 / M_PI;  // 0..90
  return std::min(to_u, 90 - to_u);
}

std::vector<double> PsnrByFootprintBand(const Image& a, const Image& b,
                                        const GrazingPlaneView& view, int texture_size,
                                        int first_row, const std::vector<double>& edges,
                                        std::vector<uint64_t>* pixels) {
  return PsnrByBand(
      a, b, first_row, [&](int i, int j) { return FootprintLength(view, i, j, texture_size); },
      edges, pixels);
}

std::vector<double> PsnrByBand(const Image& a, const Image& b, int first_row,
                               const std::function<double(int, int)>& measure,
                               const std::vector<double>& edges, std::vector<uint64_t>* pixels) {
  const size_t bands = edges.size() + 1;
  std::vector<double> sum(bands, 0);
  std::vector<uint64_t> count(bands, 0);
  for (int j = first_row; j < a.height(); ++j)
    for (int i = 0; i < a.width(); ++i) {
      const double value = measure(i, j);
      const size_t band = std::upper_bound(edges.begin(), edges.end(), value) - edges.begin();
      const Rgba &p = a.at(i, j), &q = b.at(i, j);
      sum[band] += double(p.r - q.r) * (p.r - q.r) + double(p.g - q.g) * (p.g - q.g) +
                   double(p.b - q.b) * (p.b - q.b);
      ++count[band];
    }
  std::vector<double> psnr(bands, 0);
  for (size_t k = 0; k < bands; ++k) {
    const double mse = count[k] > 0 ? sum[k] / (3.0 * static_cast<double>(count[k])) : 0;
    psnr[k] = count[k] == 0 ? 0 : mse == 0 ? INFINITY : 10.0 * std::log10(1.0 / mse);
  }
  if (pixels != nullptr) *pixels = count;
  return psnr;
}

}  // namespace aperture
