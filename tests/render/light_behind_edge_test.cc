// A light point sliding behind the slanted edge of a nearer wall, frame by frame, through the
// public frame renderer: for every filter, its energy in each frame is its analytic energy times
// the share of its footprint the wall leaves visible, computed apart from the renderer (the
// projection by the pinhole formula, the octagon clipped by the wall's screen quad,
// support/footprint_clip.h); so it falls monotonically and no step between frames exceeds the
// change of the covered area (FAA Part 60's "no blinking" for a light passing behind a wing).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "render/frame_renderer.h"
#include "scene/scene_builder.h"
#include "support/footprint_clip.h"

namespace aperture {
namespace {

constexpr int kWidth = 64, kHeight = 48;
constexpr double kExposure = 0.01, kIntensity = 30;
constexpr double kLightDepth = 40, kWallDepth = 20;
constexpr double kFootprintRadiusPx = 2;  // min_size_px 4: larger than the lamp, below the bloom
// The pixel's side on the tangent plane (60 degrees vertical field of view, square pixels).
const double kPixelTan = 2 * std::tan(Radians(30)) / kHeight;

// The pinhole projection of a camera-space point (the camera at the origin looking along -z).
Vec2 Project(const Vec3& p) {
  return {kWidth / 2.0 + p.x / -p.z / kPixelTan, kHeight / 2.0 - p.y / -p.z / kPixelTan};
}

// The light's red energy in pixel values: exposure x I / d^2 / (one pixel's solid angle there).
double AnalyticRedEnergy(const Vec3& light) {
  const double tx = light.x / -light.z, ty = light.y / -light.z;
  const double pixel_sr = kPixelTan * kPixelTan / std::pow(1 + tx * tx + ty * ty, 1.5);
  return kExposure * kIntensity / Dot(light, light) / pixel_sr;
}

double RedSum(const Image& image) {
  double sum = 0;
  for (const Rgba& p : image.texels()) sum += p.r;
  return sum;
}

// The wall: a quad 20 m ahead whose left edge leans 20 degrees from the vertical, passing through
// the light's line of sight at the light's height when the light is at x = 0.
std::vector<Vec3> WallCorners(double light_y) {
  const double lean = std::tan(Radians(20));
  const double y_at_light = light_y * kWallDepth / kLightDepth;
  auto edge_x = [&](double y) { return (y - y_at_light) * lean; };
  return {{edge_x(-3), -3, -kWallDepth},
          {4, -3, -kWallDepth},
          {4, 3, -kWallDepth},
          {edge_x(3), 3, -kWallDepth}};
}

v1::Scene WallAndLight(const std::vector<Vec3>& wall, const Vec3& light) {
  v1::Scene scene;
  scene.set_name("light behind an edge");
  v1::Material& grey = *scene.add_materials();
  grey.set_id("grey");
  grey.set_unlit(true);
  grey.mutable_base_color()->set_r(0.2f);
  grey.mutable_base_color()->set_g(0.2f);
  grey.mutable_base_color()->set_b(0.2f);
  v1::Mesh& mesh = *scene.add_meshes();
  mesh.set_id("wall");
  mesh.set_material_id("grey");
  v1::Polygon& quad = *mesh.add_polygons();
  for (const Vec3& c : wall) {
    v1::Vec3& v = *quad.add_vertices();
    v.set_x(c.x);
    v.set_y(c.y);
    v.set_z(c.z);
  }
  v1::LightPoint& lp = *scene.add_lights();
  lp.mutable_position()->set_x(light.x);
  lp.mutable_position()->set_y(light.y);
  lp.mutable_position()->set_z(light.z);
  lp.set_intensity_cd(kIntensity);
  lp.mutable_color()->set_r(1);
  lp.mutable_color()->set_g(0.5f);
  lp.mutable_color()->set_b(0.25f);
  scene.mutable_light_settings()->set_exposure(kExposure);
  scene.mutable_light_settings()->set_min_size_px(2 * kFootprintRadiusPx);
  return scene;
}

double RenderedRedSum(const v1::Scene& proto, AntiAliasing aa) {
  auto scene = BuildScene(proto);
  EXPECT_TRUE(scene.ok()) << scene.status();
  if (!scene.ok()) return NAN;
  RenderSettings settings;
  settings.width = kWidth;
  settings.height = kHeight;
  settings.aa = aa;
  settings.threads = 1;
  Camera camera;
  camera.vertical_fov_deg = 60;
  auto frame = RenderFrame(*scene, camera, settings);
  EXPECT_TRUE(frame.ok()) << frame.status();
  return frame.ok() ? RedSum(frame->image) : NAN;
}

// Per frame, the light's energy over its analytic energy (the frame less the frame without the
// light) and the visible share of its footprint.
struct EdgeFrame {
  double energy = 0, share = 0;
};

std::vector<EdgeFrame> SlideBehindTheEdge(AntiAliasing aa, double step_px, int frames) {
  const double light_y = 0.13 * kPixelTan * kLightDepth;  // off the pixel rows' centres
  const std::vector<Vec3> wall = WallCorners(light_y);
  std::vector<Vec2> wall_screen;
  for (const Vec3& c : wall) wall_screen.push_back(Project(c));
  v1::Scene dark = WallAndLight(wall, {0, light_y, -kLightDepth});
  dark.clear_lights();
  const double dark_sum = RenderedRedSum(dark, aa);
  std::vector<EdgeFrame> out;
  for (int k = 0; k < frames; ++k) {
    // From 3 pixels left of the edge to 3 pixels right of it (the footprint is 4 across).
    const double x_px = -3 + k * step_px;
    const Vec3 light{x_px * kPixelTan * kLightDepth, light_y, -kLightDepth};
    const Vec2 at = Project(light);
    EdgeFrame f;
    f.share = testing::VisibleFootprintShare(at.x, at.y, kFootprintRadiusPx, wall_screen);
    f.energy =
        (RenderedRedSum(WallAndLight(wall, light), aa) - dark_sum) / AnalyticRedEnergy(light);
    out.push_back(f);
  }
  return out;
}

TEST(LightBehindEdge, EnergyIsTheVisibleShareAndFallsMonotonicallyWithoutPops) {
  constexpr double kStepPx = 0.04;
  constexpr int kFrames = 151;
  // The float image's rounding: under 1e-7 of the light's energy on this frame. A footprint drawn
  // as a disc instead of the octagon, or hidden by a test at its centre, is off by 1e-3 and more.
  constexpr double kTolerance = 1e-5;
  for (AntiAliasing aa : {AntiAliasing::kBox2, AntiAliasing::kBox1, AntiAliasing::kTent2}) {
    const std::vector<EdgeFrame> frames = SlideBehindTheEdge(aa, kStepPx, kFrames);
    ASSERT_EQ(frames.size(), static_cast<size_t>(kFrames));
    // The slide covers all of the footprint, from wholly visible to wholly hidden, in small steps.
    EXPECT_EQ(frames.front().share, 1.0);
    EXPECT_EQ(frames.back().share, 0.0);
    double largest_share_step = 0;
    for (int k = 0; k < kFrames; ++k) {
      EXPECT_NEAR(frames[k].energy, frames[k].share, kTolerance)
          << AntiAliasingName(aa) << " frame " << k;
      if (k == 0) continue;
      const double step = frames[k - 1].energy - frames[k].energy;
      const double covered = frames[k - 1].share - frames[k].share;
      largest_share_step = std::max(largest_share_step, covered);
      EXPECT_GE(step, -kTolerance) << AntiAliasingName(aa) << " frame " << k << ": it brightened";
      EXPECT_NEAR(step, covered, kTolerance)
          << AntiAliasingName(aa) << " frame " << k << ": a step unlike the covered area's";
    }
    EXPECT_GT(largest_share_step, 0.01);
    EXPECT_LT(largest_share_step, 0.05);
  }
}

}  // namespace
}  // namespace aperture
