// Alpha (MASK and BLEND) against an independent dense reference: at each of
// 256 x 256 samples per aperture every polygon containing it is composited front to back
// (support/reference_render), with no use of the renderer's coverage code.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "raster/warnock.h"
#include "render/frame_renderer.h"
#include "render/trace_renderer.h"
#include "scene/scene_builder.h"
#include "support/reference_render.h"
#include "support/test_scenes.h"
#include "texture/image_file.h"
#include "texture/procedural.h"

namespace aperture {
namespace {

using testing::FlatPolygon;
using testing::OriginCamera;
using testing::PointAtPixel;

constexpr int kWidth = 40, kHeight = 30;
constexpr int kSamplesPerAxis = 256;
const Rgba kSky{0.1f, 0.2f, 0.9f, 1};

// Screen point (pixels) to a world point on the plane z = -depth.
Vec3 At(double px, double py, double depth) { return PointAtPixel(kWidth, kHeight, px, py, depth); }

RenderSettings Settings(AntiAliasing aa, bool transparent_sky = false) {
  RenderSettings settings;
  settings.width = kWidth;
  settings.height = kHeight;
  settings.aa = aa;
  settings.threads = 2;
  settings.transparent_sky = transparent_sky;
  return settings;
}

// Whether every polygon lies wholly inside or wholly outside the aperture of pixel (x, y) and
// the depth order of those inside is the same at its four corners (depth differences are
// screen-linear, so then everywhere in it): the composite is constant over the aperture and a
// few samples give it exactly.
bool ApertureIsUniform(const FrameGeometry& geo, double margin, int x, int y) {
  const double xs[4] = {x - margin, x + 1 + margin, x + 1 + margin, x - margin};
  const double ys[4] = {y - margin, y - margin, y + 1 + margin, y + 1 + margin};
  std::vector<const ScreenPolygon*> inside;
  for (const ScreenPolygon& p : geo.polygons) {
    bool all = true;
    for (int k = 0; k < 4; ++k) all = all && p.Contains(xs[k], ys[k]);
    if (all)
      inside.push_back(&p);
    else if (PolygonOverlapsRect(p, xs[0], ys[0], xs[2], ys[2]))
      return false;
  }
  for (const ScreenPolygon* a : inside)
    for (const ScreenPolygon* b : inside) {
      int in_front = 0;
      for (int k = 0; k < 4; ++k)
        in_front += a->inv_depth.At(xs[k], ys[k]) > b->inv_depth.At(xs[k], ys[k]);
      if (in_front != 0 && in_front != 4) return false;
    }
  return true;
}

struct Errors {
  double max = 0, rmse = 0;
  int pixels = 0, edge_pixels = 0;
  int worst_x = -1, worst_y = -1;
  Rgba worst_got, worst_want;
};

// The frame against the dense composite of the polygons' flat colours and alphas. `alpha_of`
// gives each scene polygon's alpha as the renderer should apply it (MASK: 0 or 1).
Errors Compare(const std::vector<FlatPolygon>& polygons, AntiAliasing aa, bool transparent_sky,
               const std::function<float(int)>& alpha_of) {
  auto scene = BuildScene(testing::MakeFlatScene(polygons, kSky));
  EXPECT_TRUE(scene.ok()) << scene.status();
  auto frame = RenderFrame(*scene, OriginCamera(), Settings(aa, transparent_sky));
  EXPECT_TRUE(frame.ok()) << frame.status();
  const double margin = ShapeOf(aa).margin;
  const FrameGeometry geo = ProjectScene(*scene, OriginCamera(), kWidth, kHeight, margin + 1);
  auto colour = [&](int k) {
    Rgba c = polygons[geo.polygons[k].scene_polygon].colour;
    c.a = alpha_of(geo.polygons[k].scene_polygon);
    return c;
  };
  const Rgba sky = transparent_sky ? Rgba{0, 0, 0, 0} : kSky;
  Errors e;
  double sum_sq = 0;
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) {
      const bool uniform = ApertureIsUniform(geo, margin, x, y);
      const Rgba want =
          testing::DenseCompositedPixel(geo, colour, sky, aa, x, y, uniform ? 2 : kSamplesPerAxis);
      const Rgba got = frame->image.at(x, y);
      for (double d : {got.r - want.r, got.g - want.g, got.b - want.b, got.a - want.a}) {
        if (std::abs(d) > e.max)
          e.max = std::abs(d), e.worst_x = x, e.worst_y = y, e.worst_got = got, e.worst_want = want;
        sum_sq += d * d;
      }
      ++e.pixels;
      e.edge_pixels += !uniform;
    }
  }
  e.rmse = std::sqrt(sum_sq / (4.0 * e.pixels));
  return e;
}

void ExpectExact(const std::vector<FlatPolygon>& polygons, const std::string& what,
                 const std::function<float(int)>& alpha_of) {
  for (AntiAliasing aa : {AntiAliasing::kBox1, AntiAliasing::kBox2, AntiAliasing::kTent2}) {
    for (bool transparent_sky : {false, true}) {
      if (transparent_sky && aa != AntiAliasing::kBox2) continue;
      SCOPED_TRACE(what + " with " + AntiAliasingName(aa) +
                   (transparent_sky ? ", transparent sky" : ""));
      const Errors e = Compare(polygons, aa, transparent_sky, alpha_of);
      std::printf("%s, %s%s: %d pixels (%d with edges), max error %.2e, RMSE %.2e\n", what.c_str(),
                  AntiAliasingName(aa), transparent_sky ? ", transparent sky" : "", e.pixels,
                  e.edge_pixels, e.max, e.rmse);
      EXPECT_GT(e.edge_pixels, 50);
      EXPECT_LE(e.max, 1.0 / 256) << "at pixel " << e.worst_x << "," << e.worst_y << ": got "
                                  << e.worst_got.r << " " << e.worst_got.g << " " << e.worst_got.b
                                  << " " << e.worst_got.a << ", want " << e.worst_want.r << " "
                                  << e.worst_want.g << " " << e.worst_want.b << " "
                                  << e.worst_want.a;
      EXPECT_LE(e.rmse, 1.0 / 2048);
    }
  }
}

// An opaque quad with the sky around it, three overlapping semi-transparent triangles at
// different depths (one reaching past the quad onto the sky), and one that interpenetrates the
// quad.
std::vector<FlatPolygon> LayeredScene(v1::AlphaMode mode) {
  return {
      {{At(4.2, 3.1, 20), At(33.7, 5.3, 20), At(31.1, 26.9, 20), At(6.3, 24.2, 20)},
       {0.9f, 0.8f, 0.1f, 1}},
      {{At(2.4, 8.6, 9), At(27.9, 2.2, 9), At(21.3, 20.8, 9)}, {0.1f, 0.8f, 0.3f, 0.5f}, mode},
      {{At(12.4, 6.6, 12), At(38.9, 12.2, 12), At(23.3, 28.8, 12)}, {0.8f, 0.1f, 0.6f, 0.3f}, mode},
      {{At(8.7, 14.1, 6), At(30.2, 16.7, 6), At(14.9, 29.3, 6)}, {0.2f, 0.3f, 0.95f, 0.75f}, mode},
      {{At(20.5, 9.2, 14), At(37.6, 18.4, 30), At(18.2, 22.6, 26)}, {0.6f, 0.6f, 0.6f, 0.6f}, mode},
  };
}

TEST(Transparency, BlendedLayersAreExactAgainstDenseCompositing) {
  const std::vector<FlatPolygon> polygons = LayeredScene(v1::ALPHA_MODE_BLEND);
  ExpectExact(polygons, "blend", [&](int k) { return polygons[k].colour.a; });
}

TEST(Transparency, MaskKeepsPolygonsAtOrAboveTheCutoffAndDropsTheRest) {
  std::vector<FlatPolygon> polygons = LayeredScene(v1::ALPHA_MODE_MASK);
  polygons[4].alpha_cutoff = 0.65f;  // alpha 0.6: dropped, although above the default cutoff
  // Alphas 0.5 and 0.75 are kept by the default cutoff 0.5, 0.3 is dropped.
  const float expected[] = {1, 1, 0, 1, 0};
  ExpectExact(polygons, "mask", [&](int k) { return expected[k]; });
}

TEST(Transparency, OpaqueSceneIsUnchangedByTheTransparentPathAndAlphaIsOne) {
  // The opaque path's pixels have alpha 1 whatever covers them.
  const std::vector<FlatPolygon> polygons = LayeredScene(v1::ALPHA_MODE_OPAQUE);
  auto scene = BuildScene(testing::MakeFlatScene(polygons, kSky));
  ASSERT_TRUE(scene.ok());
  auto frame = RenderFrame(*scene, OriginCamera(), Settings(AntiAliasing::kBox2));
  ASSERT_TRUE(frame.ok());
  for (const Rgba& p : frame->image.texels()) ASSERT_EQ(p.a, 1.0f);
  ExpectExact(polygons, "opaque", [](int) { return 1.0f; });
}

TEST(Transparency, ATransparentPolygonCoveringTheViewIsNotACover) {
  // Warnock would call every window covered by the front polygon; it is half transparent.
  const Rgba back{0.8f, 0.3f, 0.1f, 1}, front{0.1f, 0.4f, 0.9f, 0.25f};
  const std::vector<FlatPolygon> polygons = {
      {{At(-20, -20, 30), At(60, -20, 30), At(60, 50, 30), At(-20, 50, 30)}, back},
      {{At(-20, -20, 10), At(60, -20, 10), At(60, 50, 10), At(-20, 50, 10)},
       front,
       v1::ALPHA_MODE_BLEND},
  };
  auto scene = BuildScene(testing::MakeFlatScene(polygons, kSky));
  ASSERT_TRUE(scene.ok());
  auto frame = RenderFrame(*scene, OriginCamera(), Settings(AntiAliasing::kBox2));
  ASSERT_TRUE(frame.ok());
  EXPECT_EQ(frame->stats.covered_leaves, 0u);
  const float a = front.a;
  for (const Rgba& p : frame->image.texels()) {
    ASSERT_NEAR(p.r, a * front.r + (1 - a) * back.r, 1e-5);
    ASSERT_NEAR(p.g, a * front.g + (1 - a) * back.g, 1e-5);
    ASSERT_NEAR(p.b, a * front.b + (1 - a) * back.b, 1e-5);
  }
}

TEST(Transparency, LayersBeyondTheBoundAreDrawnOpaque) {
  // Six half-transparent quads stacked over every pixel: the four nearest are composited, the
  // two farthest drawn as if opaque (docs/SCENE.md "Alpha"), so the work of a cell stays bounded.
  std::vector<FlatPolygon> polygons;
  for (int i = 0; i < 6; ++i)
    polygons.push_back(
        {{At(-20, -20, 5 + i), At(60, -20, 5 + i), At(60, 50, 5 + i), At(-20, 50, 5 + i)},
         {0.15f * i, 1.0f - 0.1f * i, 0.5f, 0.5f},
         v1::ALPHA_MODE_BLEND});
  auto scene = BuildScene(testing::MakeFlatScene(polygons, kSky));
  ASSERT_TRUE(scene.ok());
  auto frame = RenderFrame(*scene, OriginCamera(), Settings(AntiAliasing::kBox1));
  ASSERT_TRUE(frame.ok());
  // Front to back: four at alpha 0.5, then the fifth opaque.
  double want[3] = {0, 0, 0}, transmitted = 1;
  for (int i = 0; i < 5; ++i) {
    const double alpha = i < 4 ? 0.5 : 1.0;
    const Rgba& c = polygons[i].colour;
    want[0] += transmitted * alpha * c.r, want[1] += transmitted * alpha * c.g;
    want[2] += transmitted * alpha * c.b;
    transmitted *= 1 - alpha;
  }
  for (const Rgba& p : frame->image.texels()) {
    ASSERT_NEAR(p.r, want[0], 1e-5);
    ASSERT_NEAR(p.g, want[1], 1e-5);
    ASSERT_NEAR(p.b, want[2], 1e-5);
  }
}

// A textured quad seen head-on, texel (i, j) at pixels [8 + 2i, 10 + 2i) x [4 + 2j, 6 + 2j)
// (the texture 16 x 16 texels over 32 x 32 pixels, one repeat), over an opaque backdrop.
v1::Scene TexturedQuadScene(const Image& texture, v1::AlphaMode mode, v1::TextureFilter filter) {
  const Rgba backdrop{0.2f, 0.7f, 0.3f, 1};
  v1::Scene scene = testing::MakeFlatScene(
      {{{At(-5, -5, 20), At(45, -5, 20), At(45, 35, 20), At(-5, 35, 20)}, backdrop}}, kSky);
  v1::Texture* t = scene.add_textures();
  t->set_id("cutout");
  auto png = EncodePng(texture);
  EXPECT_TRUE(png.ok());
  t->set_encoded(std::string(png->begin(), png->end()));
  v1::Material* m = scene.add_materials();
  m->set_id("leaf");
  m->set_unlit(true);
  m->set_texture_id("cutout");
  m->set_filter(filter);
  m->set_alpha_mode(mode);
  v1::Polygon* p = scene.mutable_meshes(0)->add_polygons();
  p->set_material_id("leaf");
  const double corners[4][2] = {{8, 4}, {40, 4}, {40, 36}, {8, 36}};
  const double uvs[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  for (int k = 0; k < 4; ++k) {
    const Vec3 v = At(corners[k][0], corners[k][1], 10);
    v1::Vec3* pv = p->add_vertices();
    pv->set_x(v.x), pv->set_y(v.y), pv->set_z(v.z);
    v1::Vec2* uv = p->add_uvs();
    uv->set_u(uvs[k][0]), uv->set_v(uvs[k][1]);
  }
  return scene;
}

TEST(Transparency, TextureAlphaIsFilteredLikeItsColourInEveryFilter) {
  // Uniform alpha 0.5 with colour (0.8, 0.2, 0.1): every filter gives 0.5 c + 0.5 backdrop.
  Image texture(16, 16);
  for (Rgba& t : texture.texels()) t = {0.8f, 0.2f, 0.1f, 0.5f};
  const float a = 128.0f / 255, c[3] = {204.0f / 255, 51.0f / 255, 26.0f / 255};  // as in the PNG
  const Rgba backdrop{0.2f, 0.7f, 0.3f, 1};
  for (v1::TextureFilter filter :
       {v1::TEXTURE_FILTER_NEAREST, v1::TEXTURE_FILTER_BILINEAR, v1::TEXTURE_FILTER_TRILINEAR,
        v1::TEXTURE_FILTER_ANISO, v1::TEXTURE_FILTER_OIIO}) {
    SCOPED_TRACE(v1::TextureFilter_Name(filter));
    auto scene = BuildScene(TexturedQuadScene(texture, v1::ALPHA_MODE_BLEND, filter));
    ASSERT_TRUE(scene.ok()) << scene.status();
    auto frame = RenderFrame(*scene, OriginCamera(), Settings(AntiAliasing::kBox2));
    ASSERT_TRUE(frame.ok());
    int checked = 0;
    for (int y = 6; y < 28; ++y)
      for (int x = 10; x < 38; ++x, ++checked) {
        const Rgba p = frame->image.at(x, y);
        ASSERT_NEAR(p.r, a * c[0] + (1 - a) * backdrop.r, 2e-3) << x << "," << y;
        ASSERT_NEAR(p.g, a * c[1] + (1 - a) * backdrop.g, 2e-3) << x << "," << y;
        ASSERT_NEAR(p.b, a * c[2] + (1 - a) * backdrop.b, 2e-3) << x << "," << y;
      }
    EXPECT_GT(checked, 500);
  }
}

TEST(Transparency, MaskCutsOutWhereTheTexturesAlphaIsBelowTheCutoff) {
  // A cut-out: alpha 1 on a pattern of 4 x 4-texel squares (symmetric top to bottom, so that it
  // does not depend on which way v runs), 0 elsewhere, where the colour is black as cut-out
  // textures often have it: premultiplied filtering keeps it out of the leaf's colour.
  auto opaque_at = [](int i, int j) { return ((i / 4) % 2 == 0) != (j / 4 == 1 || j / 4 == 2); };
  Image texture(16, 16);
  for (int j = 0; j < 16; ++j)
    for (int i = 0; i < 16; ++i)
      texture.at(i, j) = opaque_at(i, j) ? Rgba{0.9f, 0.5f, 0.1f, 1} : Rgba{0, 0, 0, 0};
  const Rgba backdrop{0.2f, 0.7f, 0.3f, 1};
  for (v1::TextureFilter filter :
       {v1::TEXTURE_FILTER_NEAREST, v1::TEXTURE_FILTER_TRILINEAR, v1::TEXTURE_FILTER_ANISO}) {
    SCOPED_TRACE(v1::TextureFilter_Name(filter));
    auto scene = BuildScene(TexturedQuadScene(texture, v1::ALPHA_MODE_MASK, filter));
    ASSERT_TRUE(scene.ok()) << scene.status();
    auto frame = RenderFrame(*scene, OriginCamera(), Settings(AntiAliasing::kBox2));
    ASSERT_TRUE(frame.ok());
    int leaf = 0, hole = 0;
    for (int y = 5; y < 35 && y < kHeight; ++y)
      for (int x = 9; x < 39; ++x) {
        // Texel coordinates of the pixel centre; skip pixels whose aperture or filter reaches a
        // square's border.
        const double u = (x + 0.5 - 8) / 2, v = (y + 0.5 - 4) / 2;
        const double du = std::abs(u / 4 - std::round(u / 4)) * 4,
                     dv = std::abs(v / 4 - std::round(v / 4)) * 4;
        if (du < 1.5 || dv < 1.5) continue;
        const bool opaque = opaque_at(static_cast<int>(u), static_cast<int>(v));
        const Rgba want = opaque ? Rgba{0.9f, 0.5f, 0.1f, 1} : backdrop;
        const Rgba p = frame->image.at(x, y);
        ASSERT_NEAR(p.r, want.r, 3e-3) << x << "," << y;
        ASSERT_NEAR(p.g, want.g, 3e-3) << x << "," << y;
        ASSERT_NEAR(p.b, want.b, 3e-3) << x << "," << y;
        (opaque ? leaf : hole) += 1;
      }
    EXPECT_GT(leaf, 20);
    EXPECT_GT(hole, 20);
  }
}

// Seed 003's mode: squares whose edges lie on the 1/8-pixel grid of its deepest subdivision
// (depth 3), where its coverage is exact, so the composite must match the dense one.
std::vector<FlatPolygon> GridAlignedLayers(v1::AlphaMode mode) {
  auto square = [](double x0, double y0, double x1, double y1, double depth) {
    return std::vector<Vec3>{At(x0, y0, depth), At(x1, y0, depth), At(x1, y1, depth),
                             At(x0, y1, depth)};
  };
  return {{square(3.25, 2.5, 28.75, 27.125, 30), {0.9f, 0.8f, 0.1f, 1}},
          {square(1.125, 5.25, 20.75, 26.5, 20), {0.1f, 0.8f, 0.3f, 0.5f}, mode},
          {square(10.375, 0.75, 38.5, 18.875, 15), {0.8f, 0.1f, 0.6f, 0.3f}, mode},
          {square(6.5, 9.625, 35.875, 22.25, 10), {0.2f, 0.3f, 0.95f, 0.75f}, mode}};
}

void ExpectRaytraceMatches(const std::vector<FlatPolygon>& polygons, bool transparent_sky,
                           const std::function<float(int)>& alpha_of) {
  auto scene = BuildScene(testing::MakeFlatScene(polygons, kSky));
  ASSERT_TRUE(scene.ok()) << scene.status();
  auto traced = TracedScene::Build(*scene);
  ASSERT_TRUE(traced.ok()) << traced.status();
  TraceOptions options;
  options.max_depth = 3;
  auto frame =
      (*traced)->Render(OriginCamera(), Settings(AntiAliasing::kBox1, transparent_sky), options);
  ASSERT_TRUE(frame.ok()) << frame.status();
  const FrameGeometry geo = ProjectScene(*scene, OriginCamera(), kWidth, kHeight, 1);
  auto colour = [&](int k) {
    Rgba c = polygons[geo.polygons[k].scene_polygon].colour;
    c.a = alpha_of(geo.polygons[k].scene_polygon);
    return c;
  };
  const Rgba sky = transparent_sky ? Rgba{0, 0, 0, 0} : kSky;
  double worst = 0;
  int edges = 0;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      const bool uniform = ApertureIsUniform(geo, 0, x, y);
      edges += !uniform;
      // 64 samples a side keep off the 1/8 grid, so the reference is exact there too.
      const Rgba want =
          testing::DenseCompositedPixel(geo, colour, sky, AntiAliasing::kBox1, x, y, 64);
      const Rgba got = frame->image.at(x, y);
      for (double d : {got.r - want.r, got.g - want.g, got.b - want.b, got.a - want.a})
        worst = std::max(worst, std::abs(d));
      ASSERT_NEAR(got.r, want.r, 1e-4) << x << "," << y;
      ASSERT_NEAR(got.g, want.g, 1e-4) << x << "," << y;
      ASSERT_NEAR(got.b, want.b, 1e-4) << x << "," << y;
      ASSERT_NEAR(got.a, want.a, 1e-4) << x << "," << y;
    }
  std::printf("raytrace%s: %d pixels with edges, max error %.2e\n",
              transparent_sky ? ", transparent sky" : "", edges, worst);
  EXPECT_GT(edges, 100);
}

TEST(Transparency, RaytraceCompositesBlendedLayersLikeTheRaster) {
  const std::vector<FlatPolygon> polygons = GridAlignedLayers(v1::ALPHA_MODE_BLEND);
  for (bool transparent_sky : {false, true})
    ExpectRaytraceMatches(polygons, transparent_sky, [&](int k) { return polygons[k].colour.a; });
}

TEST(Transparency, RaytraceMasksLikeTheRaster) {
  const std::vector<FlatPolygon> polygons = GridAlignedLayers(v1::ALPHA_MODE_MASK);
  const float expected[] = {1, 1, 0, 1};  // alpha 0.3 is below the default cutoff 0.5
  ExpectRaytraceMatches(polygons, false, [&](int k) { return expected[k]; });
}

TEST(Transparency, RaytraceFiltersTextureAlphaLikeItsColour) {
  Image texture(16, 16);
  for (Rgba& t : texture.texels()) t = {0.8f, 0.2f, 0.1f, 0.5f};
  const float a = 128.0f / 255, c[3] = {204.0f / 255, 51.0f / 255, 26.0f / 255};
  const Rgba backdrop{0.2f, 0.7f, 0.3f, 1};
  auto scene =
      BuildScene(TexturedQuadScene(texture, v1::ALPHA_MODE_BLEND, v1::TEXTURE_FILTER_TRILINEAR));
  ASSERT_TRUE(scene.ok()) << scene.status();
  auto traced = TracedScene::Build(*scene);
  ASSERT_TRUE(traced.ok()) << traced.status();
  auto frame = (*traced)->Render(OriginCamera(), Settings(AntiAliasing::kBox1), TraceOptions{});
  ASSERT_TRUE(frame.ok()) << frame.status();
  for (int y = 6; y < 28; ++y)
    for (int x = 10; x < 38; ++x) {
      const Rgba p = frame->image.at(x, y);
      ASSERT_NEAR(p.r, a * c[0] + (1 - a) * backdrop.r, 1e-4) << x << "," << y;
      ASSERT_NEAR(p.g, a * c[1] + (1 - a) * backdrop.g, 1e-4) << x << "," << y;
      ASSERT_NEAR(p.b, a * c[2] + (1 - a) * backdrop.b, 1e-4) << x << "," << y;
    }
}

TEST(Transparency, PngAlphaIsPremultipliedInFloat) {
  // PNG stores unassociated alpha; decoding premultiplies it in float, not in the file's 8 bits
  // (51 * 128 / 255 would round to 26 / 255 there).
  Image texture(2, 1);
  texture.at(0, 0) = {0.2f, 0.6f, 1.0f, 128.0f / 255};
  texture.at(1, 0) = {0.2f, 0.6f, 1.0f, 3.0f / 255};
  auto png = EncodePng(texture);
  ASSERT_TRUE(png.ok());
  auto decoded = DecodeImage(*png);
  ASSERT_TRUE(decoded.ok()) << decoded.status();
  for (int x = 0; x < 2; ++x) {
    const Rgba t = decoded->at(x, 0);
    const float a = texture.at(x, 0).a;
    EXPECT_FLOAT_EQ(t.a, a);
    EXPECT_FLOAT_EQ(t.r, 51.0f / 255 * a);
    EXPECT_FLOAT_EQ(t.g, 153.0f / 255 * a);
    EXPECT_FLOAT_EQ(t.b, a);
  }
}

TEST(Transparency, ScenesRefuseBadAlphaFields) {
  const std::vector<FlatPolygon> polygons = LayeredScene(v1::ALPHA_MODE_BLEND);
  v1::Scene scene = testing::MakeFlatScene(polygons, kSky);
  scene.mutable_materials(1)->set_alpha_cutoff(1.5f);
  auto built = BuildScene(scene);
  ASSERT_FALSE(built.ok());
  EXPECT_NE(built.status().message().find("alpha_cutoff"), std::string::npos) << built.status();
  scene = testing::MakeFlatScene(polygons, kSky);
  scene.mutable_materials(2)->set_transparency(std::nanf(""));
  built = BuildScene(scene);
  ASSERT_FALSE(built.ok());
  EXPECT_NE(built.status().message().find("transparency"), std::string::npos) << built.status();
  scene = testing::MakeFlatScene(polygons, kSky);
  scene.mutable_materials(0)->set_alpha_mode(static_cast<v1::AlphaMode>(7));
  built = BuildScene(scene);
  ASSERT_FALSE(built.ok());
  EXPECT_NE(built.status().message().find("alpha_mode"), std::string::npos) << built.status();
}

}  // namespace
}  // namespace aperture
