// Analytic edge anti-aliasing (seed 002, eq. 2) against an independent dense-sampling reference.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "absl/strings/str_cat.h"
#include "render/frame_renderer.h"
#include "scene/scene_builder.h"
#include "support/reference_render.h"
#include "support/test_scenes.h"

namespace aperture {
namespace {

using testing::FlatPolygon;
using testing::OriginCamera;
using testing::PointAtPixel;

constexpr int kWidth = 40, kHeight = 30;
constexpr int kSamplesPerAxis = 256;  // 65,536 samples per aperture
const Rgba kSky{0.1f, 0.2f, 0.9f, 1};

// Screen point (pixels) to a world point on the plane z = -depth.
Vec3 At(double px, double py, double depth) { return PointAtPixel(kWidth, kHeight, px, py, depth); }

struct Errors {
  double max_edge = 0, rmse_edge = 0;
  int edge_pixels = 0, interior_pixels = 0, interior_mismatches = 0;
};

Errors Compare(const std::vector<FlatPolygon>& polygons, AntiAliasing aa) {
  auto scene = BuildScene(testing::MakeFlatScene(polygons, kSky));
  EXPECT_TRUE(scene.ok()) << scene.status();
  RenderSettings settings;
  settings.width = kWidth;
  settings.height = kHeight;
  settings.aa = aa;
  settings.threads = 2;
  auto frame = RenderFrame(*scene, OriginCamera(), settings);
  EXPECT_TRUE(frame.ok()) << frame.status();
  const double margin = ShapeOf(aa).margin;
  const FrameGeometry geo = ProjectScene(*scene, OriginCamera(), kWidth, kHeight, margin + 1);
  auto colour = [&](int k) { return scene->materials[geo.polygons[k].material].base_color; };

  Errors e;
  double sum_sq = 0;
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) {
      const Rgba got = frame->image.at(x, y);
      // Interior: the aperture lies inside one polygon and no other reaches into it.
      const double x0 = x - margin, x1 = x + 1 + margin, y0 = y - margin, y1 = y + 1 + margin;
      int inside = -1, touching = 0;
      for (size_t k = 0; k < geo.polygons.size(); ++k) {
        const ScreenPolygon& p = geo.polygons[k];
        if (p.max_x <= x0 || p.min_x >= x1 || p.max_y <= y0 || p.min_y >= y1) continue;
        ++touching;
        if (p.Contains(x0, y0) && p.Contains(x1, y0) && p.Contains(x1, y1) && p.Contains(x0, y1))
          inside = static_cast<int>(k);
      }
      if (touching == 0) {
        EXPECT_EQ(got, kSky) << "sky pixel " << x << "," << y;
        continue;
      }
      if (touching == 1 && inside >= 0) {
        ++e.interior_pixels;
        const Rgba want = colour(inside);
        if (got.r != want.r || got.g != want.g || got.b != want.b) ++e.interior_mismatches;
        continue;
      }
      const Rgba want = testing::DenseReferencePixel(geo, colour, kSky, aa, x, y, kSamplesPerAxis);
      for (double d : {got.r - want.r, got.g - want.g, got.b - want.b}) {
        e.max_edge = std::max(e.max_edge, std::abs(d));
        sum_sq += d * d;
      }
      ++e.edge_pixels;
    }
  }
  e.rmse_edge = e.edge_pixels > 0 ? std::sqrt(sum_sq / (3.0 * e.edge_pixels)) : 0;
  return e;
}

void ExpectAccurate(const std::vector<FlatPolygon>& polygons, const char* what) {
  for (AntiAliasing aa : {AntiAliasing::kBox1, AntiAliasing::kBox2, AntiAliasing::kTent2}) {
    SCOPED_TRACE(std::string(what) + " with " + AntiAliasingName(aa));
    const Errors e = Compare(polygons, aa);
    std::printf("%s, %s: %d edge pixels, max error %.2e, RMSE %.2e; %d interior pixels\n", what,
                AntiAliasingName(aa), e.edge_pixels, e.max_edge, e.rmse_edge, e.interior_pixels);
    EXPECT_GT(e.edge_pixels, 10);
    EXPECT_LE(e.max_edge, 1.0 / 256);
    EXPECT_LE(e.rmse_edge, 1.0 / 2048);
    EXPECT_EQ(e.interior_mismatches, 0) << "of " << e.interior_pixels << " interior pixels";
  }
}

Rgba RandomColour(std::mt19937& rng) {
  std::uniform_real_distribution<float> u(0, 1);
  return {u(rng), u(rng), u(rng), 1};
}

TEST(EdgeAntiAliasing, ThinSlivers) {
  std::mt19937 rng(7);
  std::vector<FlatPolygon> polys;
  for (int i = 0; i < 6; ++i) {
    const double a = 0.3 + i * 0.47, cx = 20, cy = 15, len = 14;
    const double dx = std::cos(a) * len, dy = std::sin(a) * len;
    const double w = 0.15 + 0.12 * i;  // sub-pixel widths
    const double nx = -std::sin(a) * w, ny = std::cos(a) * w;
    const double depth = 10 + i;
    polys.push_back({{At(cx - dx, cy - dy, depth), At(cx + dx, cy + dy, depth),
                      At(cx + dx + nx, cy + dy + ny, depth)},
                     RandomColour(rng)});
  }
  ExpectAccurate(polys, "thin slivers");
}

TEST(EdgeAntiAliasing, FanOfTrianglesMeetingAtAVertex) {
  std::mt19937 rng(11);
  std::vector<FlatPolygon> polys;
  const int n = 13;
  for (int i = 0; i < n; ++i) {
    const double a0 = 2 * kPi * i / n + 0.1, a1 = 2 * kPi * (i + 1) / n + 0.1;
    polys.push_back(
        {{At(20.3, 14.7, 10), At(20.3 + 12 * std::cos(a0), 14.7 + 12 * std::sin(a0), 10),
          At(20.3 + 12 * std::cos(a1), 14.7 + 12 * std::sin(a1), 10)},
         RandomColour(rng)});
  }
  ExpectAccurate(polys, "fan");
}

TEST(EdgeAntiAliasing, PolygonPartlyHidingAnother) {
  std::vector<FlatPolygon> polys = {
      {{At(5.2, 4.1, 20), At(30.7, 6.3, 20), At(28.1, 25.9, 20), At(7.3, 22.2, 20)},
       {0.9f, 0.2f, 0.1f, 1}},
      // In front, drawn first: scene order must not decide visibility.
      {{At(15.4, 10.6, 8), At(37.9, 12.2, 8), At(33.3, 28.8, 8)}, {0.1f, 0.8f, 0.3f, 1}},
  };
  std::swap(polys[0], polys[1]);
  ExpectAccurate(polys, "occlusion");
}

TEST(EdgeAntiAliasing, NearHorizontalEdge) {
  std::vector<FlatPolygon> polys = {
      {{At(-2, 14.37, 10), At(42, 14.81, 10), At(42, 32, 10), At(-2, 32, 10)},
       {0.95f, 0.9f, 0.2f, 1}},
      {{At(3, 5.13, 10), At(38, 5.06, 10), At(38, 9.91, 10), At(3, 9.49, 10)},
       {0.3f, 0.1f, 0.6f, 1}},
  };
  ExpectAccurate(polys, "near-horizontal edges");
}

// A crowd of small flat triangles drawn one over another (tris-N in miniature: 60 of them with
// vertices within 4 pixels of their centres in a 16 x 12 patch, each on a plane of its own, later
// ones nearer): most
// cells hold several stacked pieces (CellCoverage::PaintStacked), and the box filters sum each
// flat leaf's cells by colour (LeafRenderer::RenderFlatBox).
TEST(EdgeAntiAliasing, CrowdOfStackedSmallTriangles) {
  std::mt19937 rng(19);
  std::uniform_real_distribution<double> centre_x(12, 28), centre_y(9, 21), unit(0, 1);
  std::vector<FlatPolygon> polys;
  for (int i = 0; i < 60; ++i) {
    const double cx = centre_x(rng), cy = centre_y(rng), depth = 40 - 0.2 * i;
    std::vector<Vec3> corners;
    for (int k = 0; k < 3; ++k) {
      const double r = 4 * std::sqrt(unit(rng)), a = 2 * kPi * unit(rng);
      corners.push_back(At(cx + r * std::cos(a), cy + r * std::sin(a), depth));
    }
    polys.push_back({corners, RandomColour(rng)});
  }
  ExpectAccurate(polys, "crowd of stacked triangles");
}

// Decals: a ground quad with markings painted on it in its own plane (no lift), overlapping one
// another, one of them placed twice at one place; a coplanar polygon is drawn over those before it
// in the scene.
TEST(EdgeAntiAliasing, CoplanarDecalsOverAGround) {
  std::mt19937 rng(23);
  // The tilted plane 0.2 x + 0.1 y - z = 10 (world), where the ray through a pixel meets it.
  auto plane = [](double px, double py) {
    const Vec3 ray = At(px, py, 1);
    return At(px, py, 10 / (0.2 * ray.x + 0.1 * ray.y - ray.z));
  };
  std::vector<FlatPolygon> polys = {
      {{plane(1, 1), plane(39, 2), plane(38, 29), plane(2, 28)}, {0.3f, 0.3f, 0.3f, 1}}};
  for (int i = 0; i < 7; ++i) {
    const double x = 5 + 4.3 * i, y = 6 + 2.1 * i;
    polys.push_back(
        {{plane(x, y), plane(x + 7.3, y + 1.1), plane(x + 6.2, y + 9.4), plane(x - 0.7, y + 8.1)},
         RandomColour(rng)});
  }
  polys.push_back(polys[3]);
  polys.back().colour = {1, 1, 0, 1};
  ExpectAccurate(polys, "coplanar decals");
}

// Object.layer decides before the scene's order: a decal listed before the ground it lies on is
// hidden by the ground, and seen over it once its object's layer is higher; its edges are exact.
TEST(EdgeAntiAliasing, LayersDecideCoplanarOverlapsBeforeTheScenesOrder) {
  const std::vector<FlatPolygon> polys = {
      {{At(12.3, 9.6, 10), At(27.8, 10.4, 10), At(26.1, 21.7, 10), At(13.4, 20.2, 10)},
       {0.9f, 0.8f, 0.1f, 1}},  // the decal, first in the scene
      {{At(2, 2, 10), At(38, 2, 10), At(38, 28, 10), At(2, 28, 10)}, {0.2f, 0.2f, 0.25f, 1}}};
  for (int decal_layer : {0, 1}) {
    v1::Scene proto = testing::MakeFlatScene(polys, kSky);
    // Each polygon its own mesh and object, the decal's object on `decal_layer`.
    const v1::Mesh all = proto.meshes(0);
    proto.clear_meshes();
    for (int i = 0; i < all.polygons_size(); ++i) {
      v1::Mesh* mesh = proto.add_meshes();
      mesh->set_id(absl::StrCat("polygon", i));
      *mesh->add_polygons() = all.polygons(i);
      v1::Object* object = proto.add_objects();
      object->set_mesh_id(mesh->id());
      object->set_layer(i == 0 ? decal_layer : 0);
    }
    auto scene = BuildScene(proto);
    ASSERT_TRUE(scene.ok()) << scene.status();
    RenderSettings settings;
    settings.width = kWidth;
    settings.height = kHeight;
    auto frame = RenderFrame(*scene, OriginCamera(), settings);
    ASSERT_TRUE(frame.ok()) << frame.status();
    const Rgba centre = frame->image.at(20, 15);
    const Rgba want = decal_layer > 0 ? polys[0].colour : polys[1].colour;
    EXPECT_EQ(centre.r, want.r) << "decal layer " << decal_layer;
    // A pixel on the decal's left edge: the dense reference with the same rule.
    const FrameGeometry geo = ProjectScene(*scene, OriginCamera(), kWidth, kHeight, 2);
    auto colour = [&](int k) { return scene->materials[geo.polygons[k].material].base_color; };
    const Rgba edge = frame->image.at(12, 15);
    const Rgba ref = testing::DenseReferencePixel(geo, colour, kSky, AntiAliasing::kBox2, 12, 15,
                                                  kSamplesPerAxis);
    EXPECT_NEAR(edge.r, ref.r, 1.0 / 256) << "decal layer " << decal_layer;
    // The ground alone there when it hides the decal, a blend over the decal's edge when not.
    EXPECT_EQ(edge.r == polys[1].colour.r, decal_layer == 0);
  }
}

// A crowd of overlapping coplanar triangles about a pixel across, 20 deep in a 6 x 5 patch, and
// the same crowd on three planes a millimetre apart at 10 m: every cell holds dozens of pieces
// whose order is the scene's (one plane) or the planes' and then the scene's.
TEST(EdgeAntiAliasing, CrowdsOfCoplanarTriangles) {
  for (int planes : {1, 3}) {
    std::mt19937 rng(29 + planes);
    std::uniform_real_distribution<double> centre_x(17, 23), centre_y(12.5, 17.5), unit(0, 1);
    std::vector<FlatPolygon> polys;
    for (int i = 0; i < 160; ++i) {
      const double cx = centre_x(rng), cy = centre_y(rng);
      const double depth = 10 + 0.001 * static_cast<int>(rng() % planes);
      std::vector<Vec3> corners;
      for (int k = 0; k < 3; ++k) {
        const double r = 1.4 * std::sqrt(unit(rng)), a = 2 * kPi * unit(rng);
        corners.push_back(At(cx + r * std::cos(a), cy + r * std::sin(a), depth));
      }
      polys.push_back({corners, RandomColour(rng)});
    }
    ExpectAccurate(polys, planes == 1 ? "coplanar crowd" : "crowd on three planes 1 mm apart");
  }
}

TEST(EdgeAntiAliasing, InterpenetratingPolygonsAreExactToo) {
  // Two quads crossing in depth along a line: the trapezoid decomposition splits at the line
  // where their depths are equal.
  const Vec3 a0 = At(6.3, 5.7, 8), a1 = At(34.2, 6.6, 17), a2 = At(20.1, 26.4, 12);
  const Vec3 b0 = At(4.4, 8.2, 15), b1 = At(36.5, 7.1, 7.5), b2 = At(18.6, 25.3, 10.5);
  ExpectAccurate({{{a0, a1, a2}, {0.8f, 0.3f, 0.2f, 1}}, {{b0, b1, b2}, {0.2f, 0.4f, 0.9f, 1}}},
                 "interpenetration");
}

TEST(EdgeAntiAliasing, SharedEdgesOfAMeshShowNoSeams) {
  // A 6 x 4 grid of quads, each split into two triangles, one colour, over a contrasting sky.
  const Rgba colour{1.0f, 0.6f, 0.0f, 1};
  std::vector<FlatPolygon> polys;
  for (int j = 0; j < 4; ++j) {
    for (int i = 0; i < 6; ++i) {
      const double x0 = 4.3 + i * 5.37, y0 = 3.9 + j * 5.61, x1 = x0 + 5.37, y1 = y0 + 5.61;
      auto d = [&](double ii, double jj) { return 10 + 0.3 * ii + 0.2 * jj; };  // tilted plane
      const Vec3 p00 = At(x0, y0, d(i, j)), p10 = At(x1, y0, d(i + 1, j));
      const Vec3 p11 = At(x1, y1, d(i + 1, j + 1)), p01 = At(x0, y1, d(i, j + 1));
      polys.push_back({{p00, p10, p11}, colour});
      polys.push_back({{p00, p11, p01}, colour});
    }
  }
  auto scene = BuildScene(testing::MakeFlatScene(polys, kSky));
  ASSERT_TRUE(scene.ok()) << scene.status();
  for (AntiAliasing aa : {AntiAliasing::kBox1, AntiAliasing::kBox2, AntiAliasing::kTent2}) {
    RenderSettings settings;
    settings.width = kWidth;
    settings.height = kHeight;
    settings.aa = aa;
    auto frame = RenderFrame(*scene, OriginCamera(), settings);
    ASSERT_TRUE(frame.ok());
    const double m = ShapeOf(aa).margin;
    double worst = 0;
    int checked = 0;
    // Pixels whose whole aperture lies inside the mesh's outline see only the mesh colour.
    for (int y = 0; y < kHeight; ++y) {
      for (int x = 0; x < kWidth; ++x) {
        if (x - m < 4.4 || x + 1 + m > 4.3 + 6 * 5.37 - 0.1 || y - m < 4.0 ||
            y + 1 + m > 3.9 + 4 * 5.61 - 0.1)
          continue;
        const Rgba got = frame->image.at(x, y);
        for (double d : {got.r - colour.r, got.g - colour.g, got.b - colour.b})
          worst = std::max(worst, std::abs(d));
        ++checked;
      }
    }
    EXPECT_GT(checked, 200);
    EXPECT_LE(worst, 1.0 / 256) << AntiAliasingName(aa);
  }
}

}  // namespace
}  // namespace aperture
