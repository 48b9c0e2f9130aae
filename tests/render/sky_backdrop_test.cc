// The sky by direction behind a frame: the grid's interpolation close to the model at every
// pixel, brighter towards the horizon in a rendered frame, and a frame in regions the same as
// whole.
#include "render/sky_backdrop.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "render/frame_renderer.h"
#include "scene/daylight.h"
#include "scene/demo_scene.h"
#include "scene/scene_builder.h"

namespace aperture {
namespace {

SkyDome Noon() { return DaylightAt(*ParseUtc("2026-06-21T12:00Z", "utc"), {52.31, 4.76}, {}).dome; }

TEST(SkyBackdrop, GridIsCloseToTheModelAtEveryPixel) {
  const SkyDome dome = Noon();
  Camera camera;
  camera.yaw_deg = 170;  // towards the sun's side
  camera.pitch_deg = 20;
  const int w = 203, h = 117;
  const SkyBackdrop sky(dome, camera, w, h, {0, 0, w, h});
  double worst = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const Rgba a = sky.At(x, y), e = SkyBackdrop::Exact(dome, camera, w, h, x, y);
      for (const auto& [got, want] : {std::pair{a.r, e.r}, {a.g, e.g}, {a.b, e.b}})
        worst = std::max(worst, static_cast<double>(std::abs(got - want) / want));
    }
  EXPECT_LT(worst, 0.02);  // under 2 % anywhere (the most near the sun)
  // The grid's nodes are exact.
  const Rgba node = sky.At(16, 8), exact = SkyBackdrop::Exact(dome, camera, w, h, 16, 8);
  EXPECT_NEAR(node.g, exact.g, 1e-6);
}

TEST(SkyBackdrop, FrameSkyIsBrighterTowardsTheHorizonAndSameInRegions) {
  v1::Scene proto = MakeDemoScene();
  proto.mutable_time_of_day()->set_utc("2026-06-21T12:00Z");
  proto.mutable_time_of_day()->mutable_place()->set_latitude_deg(52.31);
  proto.mutable_time_of_day()->mutable_place()->set_longitude_deg(4.76);
  auto scene = BuildScene(proto);
  ASSERT_TRUE(scene.ok()) << scene.status();
  Camera camera;
  camera.position = {0, 2, 0};
  camera.pitch_deg = 25;  // the horizon in the lower part of the frame
  RenderSettings settings;
  settings.width = 96;
  settings.height = 64;
  settings.threads = 1;
  auto frame = RenderFrame(*scene, camera, settings);
  ASSERT_TRUE(frame.ok()) << frame.status();
  const Image& image = frame->image;
  // Looking north at noon (the sun behind, south): the top row is higher up the sky than a row
  // just above the horizon, so darker.
  const Rgba top = image.at(48, 0), low = image.at(48, 30);
  EXPECT_EQ(top.a, 1);
  EXPECT_LT(top.g, low.g);
  EXPECT_FALSE(top.r == low.r && top.g == low.g && top.b == low.b);
  // The same frame in two regions, pixel for pixel.
  for (const PixelRect& region : {PixelRect{0, 0, 96, 27}, PixelRect{0, 27, 96, 64}}) {
    RenderSettings part = settings;
    part.region = region;
    auto piece = RenderFrame(*scene, camera, part);
    ASSERT_TRUE(piece.ok());
    for (int y = region.y0; y < region.y1; ++y)
      for (int x = region.x0; x < region.x1; ++x) {
        const Rgba a = piece->image.at(x - region.x0, y - region.y0), b = image.at(x, y);
        ASSERT_TRUE(a.r == b.r && a.g == b.g && a.b == b.b && a.a == b.a) << x << "," << y;
      }
  }
}

}  // namespace
}  // namespace aperture
