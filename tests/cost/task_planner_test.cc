#include "cost/task_planner.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>

#include "cost/rank_correlation.h"
#include "cost/window_cost.h"
#include "raster/polygon_clip.h"
#include "scene/triangulate.h"

namespace aperture {
namespace {

ScreenPolygon Square(double x0, double y0, double x1, double y1) {
  ScreenPolygon p;
  p.vertices = {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
  p.Finalize();
  return p;
}

TEST(WindowCost, FeaturesOfASquareInsideAndAcrossTheWindow) {
  FrameGeometry g;
  g.width = g.height = 64;
  g.polygons = {Square(10, 10, 20, 30), Square(28, 0, 40, 8)};
  const WindowFeatures f = MeasureWindowFeatures(g, {0, 1}, {0, 0, 32, 32}, 2);
  EXPECT_EQ(f.pixels, 1024);
  EXPECT_EQ(f.polygons, 2);
  EXPECT_NEAR(f.area, 200 + 4 * 8, 1e-9);
  // Square 0: perimeter 60, 4 vertices inside. Square 1 clipped at x = 32: its left (8) and
  // bottom (4) edges count, its top lies on the window's border y = 0 and its right is the clip;
  // one vertex, (28, 8), is inside.
  EXPECT_NEAR(f.boundary, 2 * 60 / std::sqrt(2.0) + 4 * 4 + 2 * 12 / std::sqrt(2.0) + 4 * 1, 1e-9);
}

// Random polygons across a window (triangles, 24-gons, and 40-gons, which the fixed buffers do
// not hold): the area and boundary of each polygon's part inside, computed
// here by clipping it to the window's four sides in turn (raster/polygon_clip's ClipToRect) and
// summing its own edges' lengths and vertices, equal the features bit for bit.
TEST(WindowCost, FeaturesOfPolygonsAcrossTheWindowAreThoseOfTheirClippedParts) {
  std::mt19937 rng(12);
  std::uniform_real_distribution<double> pos(-20, 52), unit(0, 1);
  const PixelRect window{0, 0, 32, 32};
  const double a = 2;
  for (int trial = 0; trial < 400; ++trial) {
    ScreenPolygon p;
    const int n = trial % 8 == 7 ? 40 : trial % 4 == 3 ? 24 : 3;
    const double cx = pos(rng), cy = pos(rng), r = 1 + 30 * unit(rng);
    for (int k = 0; k < n; ++k) {
      const double t = 2 * M_PI * (k + 0.5 * unit(rng)) / n;
      p.vertices.push_back({cx + r * std::cos(t), cy + r * std::sin(t)});
    }
    p.Finalize();
    FrameGeometry g;
    g.width = g.height = 64;
    g.polygons = {p};
    const WindowFeatures f = MeasureWindowFeatures(g, {0}, window, a);

    std::vector<Vec2> part(p.vertices.begin(), p.vertices.end()), scratch;
    ClipToRect(part, 0, 0, 32, 32, scratch);
    double area = 0, boundary = 0;
    const bool covers = p.ContainsRect(0, 0, 32, 32);
    const bool inside = p.min_x > 0 && p.max_x < 32 && p.min_y > 0 && p.max_y < 32;
    if (covers) {
      area = 1024;
    } else if (inside) {
      area = p.area;
      boundary = a * p.perimeter / std::sqrt(2.0) + a * a * n;
    } else if (!part.empty()) {
      area = std::abs(SignedArea(part));
      double length = 0;
      for (size_t k = 0; k < part.size(); ++k) {
        const Vec2& s = part[k];
        const Vec2& e = part[(k + 1) % part.size()];
        const bool on_border =
            (s.x == e.x && (s.x == 0 || s.x == 32)) || (s.y == e.y && (s.y == 0 || s.y == 32));
        if (!on_border) length += std::sqrt((e.x - s.x) * (e.x - s.x) + (e.y - s.y) * (e.y - s.y));
      }
      int vertices = 0;
      for (const Vec2& v : p.vertices) vertices += v.x > 0 && v.x < 32 && v.y > 0 && v.y < 32;
      boundary = a * length / std::sqrt(2.0) + a * a * vertices;
    }
    ASSERT_EQ(f.area, area) << "trial " << trial;
    ASSERT_EQ(f.boundary, boundary) << "trial " << trial;
  }
}

TEST(WindowCost, FitRecoversTheConstants) {
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> u(0, 1);
  const CostModel truth{0.02, 0.1, 0.5};
  std::vector<WindowFeatures> features;
  std::vector<double> times;
  for (int i = 0; i < 200; ++i) {
    WindowFeatures f;
    f.pixels = 1024;
    f.area = 2000 * u(rng);
    f.boundary = 300 * u(rng);
    features.push_back(f);
    times.push_back(truth.Predict(f) * (1 + 0.01 * (u(rng) - 0.5)));
  }
  const CostModel fit = FitCostModel(features, times);
  EXPECT_NEAR(fit.per_pixel, 0.02, 0.005);
  EXPECT_NEAR(fit.per_area, 0.1, 0.005);
  EXPECT_NEAR(fit.per_boundary, 0.5, 0.02);
}

TEST(WindowCost, StoredModelRoundTripsAndBadFilesAreRejected) {
  const auto dir = std::filesystem::temp_directory_path() / ("cost_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::string good = (dir / "m.txt").string(), bad = (dir / "bad.txt").string();
  ASSERT_TRUE(SaveCostModel({0.5, 0.25, 2}, good).ok());
  auto m = LoadCostModel(good);
  ASSERT_TRUE(m.ok());
  EXPECT_EQ(m->per_boundary, 2);
  std::ofstream(bad) << "0.1 nan 3";
  EXPECT_FALSE(LoadCostModel(bad).ok());
  EXPECT_EQ(LoadCostModel((dir / "missing").string()).status().code(), absl::StatusCode::kNotFound);
  std::filesystem::remove_all(dir);
}

TEST(RankCorrelation, MonotoneIsOneReversedIsMinusOne) {
  EXPECT_NEAR(SpearmanCorrelation({1, 2, 3, 4}, {10, 20, 30, 400}), 1.0, 1e-12);
  EXPECT_NEAR(SpearmanCorrelation({1, 2, 3, 4}, {4, 3, 2, 1}), -1.0, 1e-12);
  EXPECT_NEAR(SpearmanCorrelation({1, 1, 2, 2}, {1, 1, 2, 2}), 1.0, 1e-12);  // ties
}

TEST(TaskPlanner, CostPlanCoversTheRegionOnceMostExpensiveFirst) {
  FrameGeometry g;
  g.width = 300;
  g.height = 200;
  std::mt19937 rng(8);
  std::uniform_real_distribution<double> x(0, 80), y(0, 60);
  for (int i = 0; i < 300; ++i) {  // a crowd in the top-left corner
    const double x0 = x(rng), y0 = y(rng);
    g.polygons.push_back(Square(x0, y0, x0 + 5, y0 + 3));
  }
  const PixelRect region{10, 5, 290, 195};
  for (Scheduling mode : {Scheduling::kCost, Scheduling::kUniform}) {
    SchedulingOptions options;
    options.mode = mode;
    options.model = CostModel{0.01, 0.1, 0.5};
    const auto tasks = PlanTasks(g, ShapeOf(AntiAliasing::kBox2), region, options, 2);
    std::vector<int> covered(static_cast<size_t>(g.width) * g.height, 0);
    for (const TaskWindow& t : tasks)
      for (int yy = t.rect.y0; yy < t.rect.y1; ++yy)
        for (int xx = t.rect.x0; xx < t.rect.x1; ++xx) ++covered[yy * g.width + xx];
    for (int yy = 0; yy < g.height; ++yy)
      for (int xx = 0; xx < g.width; ++xx) {
        const bool inside = xx >= 10 && xx < 290 && yy >= 5 && yy < 195;
        ASSERT_EQ(covered[yy * g.width + xx], inside ? 1 : 0) << xx << "," << yy;
      }
    if (mode == Scheduling::kCost) {
      for (size_t i = 1; i < tasks.size(); ++i)
        EXPECT_GE(tasks[i - 1].predicted_us, tasks[i].predicted_us);
      // The crowded corner is cut finer than the empty rest.
      EXPECT_LT(tasks.front().rect.pixels(), tasks.back().rect.pixels());
    }
  }
}

TEST(TaskPlanner, RunsOfSkyStopAtTheGrain) {
  // An empty 640 x 320 frame: 10 x 5 root windows of equal predicted cost. Planned for one worker
  // (16 tasks per thread) the grain is 1/16 of the total, so a run holds at most 3 of the 50 roots.
  FrameGeometry g;
  g.width = 640;
  g.height = 320;
  SchedulingOptions options;
  options.model = CostModel{0.01, 0.1, 0.5};
  const PixelRect region{0, 0, 640, 320};
  const auto tasks = PlanTasks(g, ShapeOf(AntiAliasing::kBox2), region, options, 1);
  double total = 0;
  for (const TaskWindow& t : tasks) total += t.predicted_us;
  ASSERT_NEAR(total, 0.01 * 640 * 320, 1e-6);
  long long pixels = 0;
  for (const TaskWindow& t : tasks) {
    EXPECT_LE(t.predicted_us, total / 16 + 1e-9);
    EXPECT_LE(t.rect.width(), 3 * 64);
    pixels += t.rect.pixels();
  }
  EXPECT_EQ(pixels, 640 * 320);
  EXPECT_EQ(tasks.size(), 20u);  // every row: runs of 3, 3, 3 and 1 roots
}

}  // namespace
}  // namespace aperture
