// Seed 003's raytrace mode on a textured sphere and a capped, lit cylinder:
// against the dense reference (each pixel's square integrated by 64 x 64 samples of the
// continuous texture) it must score at least as high as what a renderer without the pixel
// integral gets: the bilinear texture point-sampled at the pixel centre, and supersampled 2 x 2,
// 4 x 4 and 8 x 8. The raster mode refuses such scenes with a clear error.
#include <gtest/gtest.h>

#include <cstdio>

#include "render/frame_renderer.h"
#include "render/trace_renderer.h"
#include "scene/scene_builder.h"
#include "testing/curved_scenes.h"
#include "testing/grazing_plane.h"
#include "testing/supersample_reference.h"

namespace aperture {
namespace {

constexpr int kSize = 48;

struct Scores {
  double raytrace, centre, ss2, ss4, ss8;
  double mean_relative_error;
};

Scores Measure(CurvedSceneKind kind) {
  const CurvedTestScene test = MakeCurvedTestScene(kind);
  auto scene = BuildScene(test.scene);
  EXPECT_TRUE(scene.ok()) << scene.status();
  auto traced = TracedScene::Build(*scene);
  EXPECT_TRUE(traced.ok()) << traced.status();
  RenderSettings settings;
  settings.width = settings.height = kSize;
  settings.threads = 2;
  TraceOptions options;  // delta 0.1, depth 3
  TraceStats stats;
  auto frame = (*traced)->Render(test.camera, settings, options, &stats);
  EXPECT_TRUE(frame.ok()) << frame.status();
  const RayScene& rays = (*traced)->rays();
  const Image ref = RenderSupersampled(*scene, rays, test.camera, kSize, kSize, {64, true});
  const Image centre = RenderSupersampled(*scene, rays, test.camera, kSize, kSize, {1, false});
  const Image ss2 = RenderSupersampled(*scene, rays, test.camera, kSize, kSize, {2, true});
  const Image ss4 = RenderSupersampled(*scene, rays, test.camera, kSize, kSize, {4, true});
  const Image ss8 = RenderSupersampled(*scene, rays, test.camera, kSize, kSize, {8, true});
  Scores s{Psnr(frame->image, ref, 0), Psnr(centre, ref, 0), Psnr(ss2, ref, 0),
           Psnr(ss4, ref, 0),          Psnr(ss8, ref, 0),    stats.fragments.MeanRelativeError()};
  std::printf(
      "%s: raytrace %.2f dB, centre %.2f, 2x2 %.2f, 4x4 %.2f, 8x8 %.2f; mean S_frag/S_quad - 1 "
      "= %.4f, %zu subdivided pixels\n",
      test.scene.name().c_str(), s.raytrace, s.centre, s.ss2, s.ss4, s.ss8, s.mean_relative_error,
      stats.subdivided_pixels);
  EXPECT_GT(stats.subdivided_pixels, 0u);  // the silhouette
  return s;
}

TEST(CurvedRender, TexturedSphereBeatsPointAndSupersampledBilinear) {
  const Scores s = Measure(CurvedSceneKind::kSphere);
  EXPECT_GE(s.raytrace, 50.0);  // measured 52.9 dB
  EXPECT_GE(s.raytrace, s.centre);
  EXPECT_GE(s.raytrace, s.ss2);
  EXPECT_GE(s.raytrace, s.ss4);
  EXPECT_GE(s.raytrace, s.ss8);
  EXPECT_LE(s.mean_relative_error, 0.1);
}

TEST(CurvedRender, TexturedLitCylinderBeatsPointAndSupersampledBilinear) {
  const Scores s = Measure(CurvedSceneKind::kCylinder);
  EXPECT_GE(s.raytrace, 52.0);  // measured 55.4 dB
  EXPECT_GE(s.raytrace, s.centre);
  EXPECT_GE(s.raytrace, s.ss2);
  EXPECT_GE(s.raytrace, s.ss4);
  EXPECT_GE(s.raytrace, s.ss8);
  EXPECT_LE(s.mean_relative_error, 0.1);
}

TEST(CurvedRender, RasterModeRefusesCurvedPrimitives) {
  auto scene = BuildScene(MakeCurvedTestScene(CurvedSceneKind::kSphere).scene);
  ASSERT_TRUE(scene.ok());
  RenderSettings settings;
  settings.width = settings.height = 16;
  auto frame = RenderFrame(*scene, Camera{}, settings);
  ASSERT_FALSE(frame.ok());
  EXPECT_EQ(frame.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_NE(std::string(frame.status().message()).find("--mode raytrace"), std::string::npos)
      << frame.status();
}

}  // namespace
}  // namespace aperture
