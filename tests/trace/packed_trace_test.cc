// Packed vector textures (seed 001) in the raytrace mode: the fragments of each pixel's
// projection are integrated by the packed format's exact area integral over its runs, without
// unpacking. Texels are constant squares, so a face-on pixel over one texel is that texel's
// colour, and a pixel over the corners of four texels their mean.
#include <gtest/gtest.h>

#include <random>

#include "render/trace_renderer.h"
#include "scene/scene.h"
#include "texture/packed/palette.h"
#include "texture/packed/rgba8_image.h"

namespace aperture {
namespace {

constexpr int kN = 16;

struct PackedCase {
  packed::IndexedImage image;
  Scene scene;
};

// A random 16 x 16 palette image on the plane z = -1 seen face-on over exactly the 16 x 16 image
// (camera at the origin, fov 90), shifted by `shift` texels along both axes.
PackedCase MakeCase(packed::Curve curve, double shift) {
  PackedCase c;
  c.image.width = c.image.height = kN;
  c.image.palette = {packed::PackRgba8(0, 0, 0, 255), packed::PackRgba8(255, 255, 255, 255),
                     packed::PackRgba8(200, 30, 60, 255), packed::PackRgba8(10, 140, 250, 255)};
  std::mt19937 rng(7);
  for (int k = 0; k < kN * kN; ++k) c.image.indices.push_back(static_cast<uint8_t>(rng() % 4));
  auto texture = packed::PackTexture(c.image, curve);
  EXPECT_TRUE(texture.ok()) << texture.status();
  c.scene.textures.push_back(MakePackedSceneTexture("packed", std::move(*texture)));
  Material m;
  m.unlit = true;
  m.texture = 0;
  c.scene.materials.push_back(m);
  ScenePolygon p;
  p.vertices = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1}};
  p.normal = {0, 0, 1};
  p.mapping.su = {0.5, 0, 0};
  p.mapping.u0 = 0.5 + shift / kN;
  p.mapping.sv = {0, -0.5, 0};
  p.mapping.v0 = 0.5 + shift / kN;
  c.scene.polygons.push_back(p);
  return c;
}

Rgba TexelColour(const packed::IndexedImage& image, int x, int y) {
  const uint32_t c =
      image.palette[image.indices[static_cast<size_t>((y + kN) % kN) * kN + (x + kN) % kN]];
  return {packed::Channel(c, 0) / 255.0f, packed::Channel(c, 1) / 255.0f,
          packed::Channel(c, 2) / 255.0f, 1};
}

RenderedFrame Render(const Scene& scene, TraceStats* stats) {
  auto traced = TracedScene::Build(scene);
  EXPECT_TRUE(traced.ok()) << traced.status();
  Camera camera;
  camera.vertical_fov_deg = 90;
  camera.near = 0.01;
  RenderSettings settings;
  settings.width = settings.height = kN;
  settings.threads = 2;
  auto frame = (*traced)->Render(camera, settings, {}, stats);
  EXPECT_TRUE(frame.ok()) << frame.status();
  return *std::move(frame);
}

TEST(PackedTrace, PixelOverOneTexelIsItsColour) {
  for (const packed::Curve curve : {packed::Curve::kHilbert, packed::Curve::kMorton}) {
    const PackedCase c = MakeCase(curve, 0);
    TraceStats stats;
    const RenderedFrame frame = Render(c.scene, &stats);
    for (int j = 0; j < kN; ++j)
      for (int i = 0; i < kN; ++i) {
        const Rgba want = TexelColour(c.image, i, j), got = frame.image.at(i, j);
        EXPECT_NEAR(got.r, want.r, 1e-5) << i << "," << j;
        EXPECT_NEAR(got.g, want.g, 1e-5) << i << "," << j;
        EXPECT_NEAR(got.b, want.b, 1e-5) << i << "," << j;
      }
    EXPECT_EQ(stats.fragments.quads, kN * kN);  // every pixel through the fragments
  }
}

TEST(PackedTrace, PixelOverFourTexelCornersIsTheirMean) {
  // Shifted by half a texel: pixel (i, j) covers [i + 0.5, i + 1.5] x [j + 0.5, j + 1.5] texels
  // (wrapping at the border), a quarter of each of four texels.
  const PackedCase c = MakeCase(packed::Curve::kHilbert, 0.5);
  TraceStats stats;
  const RenderedFrame frame = Render(c.scene, &stats);
  for (int j = 0; j < kN; ++j)
    for (int i = 0; i < kN; ++i) {
      const Rgba want = (TexelColour(c.image, i, j) + TexelColour(c.image, i + 1, j) +
                         TexelColour(c.image, i, j + 1) + TexelColour(c.image, i + 1, j + 1)) *
                        0.25f;
      const Rgba got = frame.image.at(i, j);
      EXPECT_NEAR(got.r, want.r, 1e-5) << i << "," << j;
      EXPECT_NEAR(got.b, want.b, 1e-5) << i << "," << j;
    }
}

}  // namespace
}  // namespace aperture
