#include "cost/window_cost.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <optional>
#include <span>

#include "absl/strings/str_cat.h"
#include "raster/polygon_clip.h"
#include "scene/triangulate.h"

namespace aperture {

WindowFeatures MeasureWindowFeatures(const FrameGeometry& geo, const std::vector<int>& polygons,
                                     const PixelRect& rect, double a) {
  WindowFeatures f;
  f.pixels = static_cast<double>(rect.pixels());
  const double x0 = rect.x0, y0 = rect.y0, x1 = rect.x1, y1 = rect.y1;
  std::vector<Vec2> poly, scratch;
  constexpr size_t kCutBuffer = 32;
  Vec2 cut[2][kCutBuffer];
  for (int index : polygons) {
    const ScreenPolygon& p = geo.polygons[index];
    if (p.max_x <= x0 || p.min_x >= x1 || p.max_y <= y0 || p.min_y >= y1) continue;
    if (p.ContainsRect(x0, y0, x1, y1)) {
      ++f.polygons;  // covers the window (the ground): all area, no edges
      f.area += f.pixels;
      continue;
    }
    // A polygon strictly inside the window (most of a dense part of a frame) needs no clipping,
    // and its area and edges are its own (no edge on the window's border): kept by
    // ScreenPolygon::Finalize, the same sums, so its vertices are not read at all.
    const bool inside = !(p.min_x <= x0 || p.max_x >= x1 || p.min_y <= y0 || p.max_y >= y1);
    if (inside) {
      ++f.polygons;
      f.area += p.area;
      f.boundary +=
          a * p.perimeter / std::sqrt(2.0) + a * a * static_cast<double>(p.vertices.size());
      continue;
    }
    // Cut to the window by only the sides that cross its box (the others leave every vertex as
    // it is, as ClipToRect does), in two fixed buffers: a crowded frame's planning cut some
    // 60,000 polygons to their windows, each through four vector clips.
    std::span<const Vec2> part;
    size_t n = kClipOverflow;  // kClipOverflow: cut in vectors below
    if (p.vertices.size() + 4 <= kCutBuffer) {
      Vec2* from = cut[0];
      Vec2* to = cut[1];
      std::copy(p.vertices.begin(), p.vertices.end(), from);
      n = p.vertices.size();
      const bool crosses[4] = {(p.min_x < x0), (p.max_x > x1), (p.min_y < y0), (p.max_y > y1)};
      const double sides[4][3] = {{1, 0, -x0}, {-1, 0, x1}, {0, 1, -y0}, {0, -1, y1}};
      for (int side = 0; side < 4 && n >= 3 && n != kClipOverflow; ++side) {
        if (!crosses[side]) continue;
        n = ClipByHalfPlane(from, n, sides[side][0], sides[side][1], sides[side][2], to,
                            kCutBuffer);
        std::swap(from, to);
      }
      if (n != kClipOverflow && n >= 3) part = {from, n};
    }
    // Too many vertices for the buffers, or rounding made a cut cross more than twice.
    if (n == kClipOverflow) {
      poly.assign(p.vertices.begin(), p.vertices.end());
      ClipToRect(poly, x0, y0, x1, y1, scratch);
      part = poly;
    }
    if (part.empty()) continue;
    ++f.polygons;
    f.area += std::abs(SignedArea(part));
    // seed 002, eq. 6: the edges widen the polygon by at most a / sqrt(2) on each side, each
    // vertex adds at most a^2. Edges on the window's border are the clip's, not the polygon's.
    double edge_length = 0;
    for (size_t k = 0; k < part.size(); ++k) {
      const Vec2& s = part[k];
      const Vec2& e = part[k + 1 == part.size() ? 0 : k + 1];
      const bool on_border =
          (s.x == e.x && (s.x == x0 || s.x == x1)) || (s.y == e.y && (s.y == y0 || s.y == y1));
      // (sqrt, not hypot: screen coordinates never come near overflow, and hypot is slow.)
      if (!on_border)
        edge_length += std::sqrt((e.x - s.x) * (e.x - s.x) + (e.y - s.y) * (e.y - s.y));
    }
    int vertices = 0;
    for (const Vec2& v : p.vertices) vertices += v.x > x0 && v.x < x1 && v.y > y0 && v.y < y1;
    f.boundary += a * edge_length / std::sqrt(2.0) + a * a * vertices;
  }
  return f;
}

CostModel FitCostModel(const std::vector<WindowFeatures>& features,
                       const std::vector<double>& microseconds) {
  // Normal equations over the active columns; a column whose weight comes out negative is
  // dropped and the rest refitted (non-negative least squares for three unknowns).
  bool active[3] = {true, true, true};
  double k[3] = {0, 0, 0};
  for (int round = 0; round < 3; ++round) {
    double m[3][3] = {}, r[3] = {};
    for (size_t i = 0; i < features.size(); ++i) {
      // Relative errors: every tile counts, cheap sky tiles as much as busy ones (what ranking
      // and balancing need), so each row is divided by its time.
      const double w = 1.0 / std::max(microseconds[i], 1.0);
      const double x[3] = {features[i].pixels * w, features[i].area * w, features[i].boundary * w};
      const double y = microseconds[i] * w;
      for (int p = 0; p < 3; ++p) {
        r[p] += active[p] ? x[p] * y : 0;
        for (int q = 0; q < 3; ++q) m[p][q] += active[p] && active[q] ? x[p] * x[q] : 0;
      }
    }
    for (int p = 0; p < 3; ++p)
      if (!active[p]) m[p][p] = 1;
    // Gaussian elimination with partial pivoting.
    for (int c = 0; c < 3; ++c) {
      int pivot = c;
      for (int row = c + 1; row < 3; ++row)
        if (std::abs(m[row][c]) > std::abs(m[pivot][c])) pivot = row;
      std::swap(m[c], m[pivot]);
      std::swap(r[c], r[pivot]);
      if (m[c][c] == 0) continue;
      for (int row = 0; row < 3; ++row) {
        if (row == c) continue;
        const double factor = m[row][c] / m[c][c];
        for (int q = 0; q < 3; ++q) m[row][q] -= factor * m[c][q];
        r[row] -= factor * r[c];
      }
    }
    bool negative = false;
    for (int p = 0; p < 3; ++p) {
      k[p] = active[p] && m[p][p] != 0 ? r[p] / m[p][p] : 0;
      if (k[p] < 0) active[p] = false, negative = true;
    }
    if (!negative) break;
  }
  return {std::max(0.0, k[0]), std::max(0.0, k[1]), std::max(0.0, k[2])};
}

absl::StatusOr<CostModel> LoadCostModel(const std::string& path) {
  std::ifstream in(path);
  if (!in) return absl::NotFoundError(absl::StrCat("no cost model at '", path, "'"));
  CostModel m;
  if (!(in >> m.per_pixel >> m.per_area >> m.per_boundary) || !std::isfinite(m.per_pixel) ||
      !std::isfinite(m.per_area) || !std::isfinite(m.per_boundary) || m.per_pixel < 0 ||
      m.per_area < 0 || m.per_boundary < 0)
    return absl::InvalidArgumentError(
        absl::StrCat("cost model '", path, "' must hold three non-negative numbers"));
  return m;
}

absl::Status SaveCostModel(const CostModel& m, const std::string& path) {
  std::ofstream out(path);
  out << m.per_pixel << " " << m.per_area << " " << m.per_boundary << "\n";
  if (!out) return absl::InternalError(absl::StrCat("cannot write cost model '", path, "'"));
  return absl::OkStatus();
}

std::vector<std::string> CostModelSearchPath() {
  std::vector<std::string> paths;
  if (const char* env = std::getenv("APERTURE_COST_MODEL"); env != nullptr && *env != '\0')
    paths.emplace_back(env);
  std::error_code error;
  const std::filesystem::path program = std::filesystem::read_symlink("/proc/self/exe", error);
  if (!error)
    paths.push_back(
        (program.parent_path().parent_path() / "share/aperture/cost_model.txt").string());
  paths.emplace_back(APERTURE_INSTALL_DATADIR "/aperture/cost_model.txt");
  return paths;
}

namespace {

struct ProcessCostModel {
  std::mutex mutex;
  std::optional<CostModel> model;  // unset: not chosen yet
  std::string source;
};

ProcessCostModel& Process() {
  static ProcessCostModel process;
  return process;
}

}  // namespace

absl::Status UseCostModelFile(const std::string& path) {
  auto model = LoadCostModel(path);
  if (!model.ok()) return model.status();
  ProcessCostModel& p = Process();
  const std::lock_guard<std::mutex> lock(p.mutex);
  p.model = *model;
  p.source = path;
  return absl::OkStatus();
}

CostModel DefaultCostModel() {
  // Every RenderSettings starts from this model: the files are read once per process.
  ProcessCostModel& p = Process();
  const std::lock_guard<std::mutex> lock(p.mutex);
  if (!p.model) {
    p.model = CostModel{};
    p.source = "built-in defaults";
    for (const std::string& path : CostModelSearchPath()) {
      if (auto stored = LoadCostModel(path); stored.ok()) {
        p.model = *stored;
        p.source = path;
        break;
      }
    }
  }
  return *p.model;
}

std::string DefaultCostModelSource() {
  DefaultCostModel();
  ProcessCostModel& p = Process();
  const std::lock_guard<std::mutex> lock(p.mutex);
  return p.source;
}

}  // namespace aperture
