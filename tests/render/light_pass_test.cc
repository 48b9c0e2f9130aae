// Light points (render/light_pass.h) against independent references: a light's pixels sum to its
// analytic energy wherever it falls inside a pixel, for every filter; a light half covered by an
// edge keeps the share of its footprint that dense sampling finds visible; a light sliding behind
// an edge dims continuously; the fog's transmission and halo carry the energies of their formulas;
// a group's update equals a fresh build of the changed scene; the ground a light stands on does
// not hide it.
#include "render/light_pass.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "render/frame_renderer.h"
#include "scene/light_points.h"
#include "scene/scene_builder.h"
#include "scene/scene_update.h"
#include "scene/triangulate.h"

namespace aperture {
namespace {

constexpr int kWidth = 64, kHeight = 48;
constexpr double kExposure = 0.01;

v1::Scene OneLight(double x, double y, double z, double intensity) {
  v1::Scene scene;
  scene.set_name("one light");
  v1::LightPoint& light = *scene.add_lights();
  light.mutable_position()->set_x(x);
  light.mutable_position()->set_y(y);
  light.mutable_position()->set_z(z);
  light.set_intensity_cd(intensity);
  light.mutable_color()->set_r(1);
  light.mutable_color()->set_g(0.5f);
  light.mutable_color()->set_b(0.25f);
  light.set_group("lamps");
  scene.mutable_light_settings()->set_exposure(kExposure);
  return scene;
}

Camera OriginCamera() {
  Camera camera;
  camera.vertical_fov_deg = 60;
  return camera;
}

RenderSettings Settings(AntiAliasing aa) {
  RenderSettings settings;
  settings.width = kWidth;
  settings.height = kHeight;
  settings.aa = aa;
  settings.threads = 1;
  return settings;
}

Image Render(const v1::Scene& proto, const Camera& camera, AntiAliasing aa,
             double scene_time_s = 0) {
  auto scene = BuildScene(proto);
  EXPECT_TRUE(scene.ok()) << scene.status();
  RenderSettings settings = Settings(aa);
  settings.scene_time_s = scene_time_s;
  auto frame = RenderFrame(*scene, camera, settings);
  EXPECT_TRUE(frame.ok()) << frame.status();
  return frame.ok() ? frame->image : Image();
}

// The sum of the frame's red channel.
double RedSum(const Image& image) {
  double sum = 0;
  for (const Rgba& p : image.texels()) sum += p.r;
  return sum;
}

// A light's energy in pixel values, from its definition: exposure x E / (one pixel's solid
// angle), E = I / d^2; the pixel's solid angle from the camera's tangent plane at the light.
double AnalyticEnergy(const Vec3& light, double intensity) {
  const double tan_half = std::tan(Radians(30));
  const double pixel_tan = 2 * tan_half / kHeight;  // square pixels
  const double tx = light.x / -light.z, ty = light.y / -light.z;
  const double pixel_sr = pixel_tan * pixel_tan / std::pow(1 + tx * tx + ty * ty, 1.5);
  return kExposure * intensity / Dot(light, light) / pixel_sr;
}

TEST(LightPass, ThePixelSumIsTheAnalyticEnergyWhereverTheLightFalls) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> across(-8, 8), deep(-60, -20);
  for (AntiAliasing aa : {AntiAliasing::kBox1, AntiAliasing::kBox2, AntiAliasing::kTent2}) {
    for (int trial = 0; trial < 20; ++trial) {
      const Vec3 p{across(rng), across(rng) * 0.7, deep(rng)};
      const double intensity = 40;
      const Image image = Render(OneLight(p.x, p.y, p.z, intensity), OriginCamera(), aa);
      const double want = AnalyticEnergy(p, intensity);
      EXPECT_NEAR(RedSum(image), want, 1e-6 * want)
          << AntiAliasingName(aa) << " light at " << p.x << ", " << p.y << ", " << p.z;
    }
  }
}

TEST(LightPass, AFrameWithoutLightPointsHasNone) {
  auto scene = BuildScene(OneLight(0.5, 0.3, -30, 40));
  ASSERT_TRUE(scene.ok()) << scene.status();
  RenderSettings settings = Settings(AntiAliasing::kBox2);
  auto lit = RenderFrame(*scene, OriginCamera(), settings);
  settings.draw_light_points = false;
  auto dark = RenderFrame(*scene, OriginCamera(), settings);
  ASSERT_TRUE(lit.ok() && dark.ok());
  EXPECT_GT(RedSum(lit->image), 0.5 * AnalyticEnergy({0.5, 0.3, -30}, 40));
  EXPECT_EQ(RedSum(dark->image), 0);
  EXPECT_EQ(dark->stats.lights_drawn, 0u);
}

// Under the tent filter, which reproduces linear functions, the image's centroid is the light's
// projection: a slide of a hundredth of a pixel moves it by that much.
TEST(LightPass, TheCentroidFollowsTheProjectionContinuously) {
  const double depth = 40, pixel = 2 * std::tan(Radians(30)) / kHeight * depth;
  double last_x = -1;
  for (int step = 0; step <= 100; ++step) {
    const double x = 0.3 + step * 0.01 * pixel;
    const Image image = Render(OneLight(x, 0, -depth, 30), OriginCamera(), AntiAliasing::kTent2);
    double sum = 0, moment = 0;
    for (int py = 0; py < kHeight; ++py)
      for (int px = 0; px < kWidth; ++px) {
        sum += image.at(px, py).r;
        moment += image.at(px, py).r * (px + 0.5);
      }
    const double centroid = moment / sum;
    const double want = kWidth / 2.0 + x / pixel;
    EXPECT_NEAR(centroid, want, 1e-6) << "step " << step;
    if (last_x >= 0) {
      EXPECT_NEAR(centroid - last_x, 0.01, 1e-6) << "step " << step;
    }
    last_x = centroid;
  }
}

// Walls (quads in front of the light) whose edges pass through the footprint: the light keeps
// the share of its footprint that 1024 x 1024 samples find outside the walls' screen polygons.
double VisibleShareBySampling(const std::vector<ScreenPolygon>& walls, double x, double y,
                              double radius) {
  // The regular octagon of the disc's area (2 sqrt(2) R^2 = pi r^2), edges along the axes and
  // diagonals, as the pass draws a footprint.
  const double circumradius = radius * std::sqrt(kPi / (2 * std::sqrt(2.0)));
  ScreenPolygon octagon;
  for (int k = 0; k < 8; ++k) {
    const double a = (k + 0.5) * kPi / 4;
    octagon.vertices.push_back({x + circumradius * std::cos(a), y + circumradius * std::sin(a)});
  }
  if (SignedArea(octagon.vertices) < 0)
    std::reverse(octagon.vertices.begin(), octagon.vertices.end());
  int inside = 0, visible = 0;
  constexpr int n = 1024;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const double sx = x - circumradius + 2 * circumradius * (i + 0.5) / n;
      const double sy = y - circumradius + 2 * circumradius * (j + 0.5) / n;
      if (!octagon.Contains(sx, sy)) continue;
      ++inside;
      visible += std::none_of(walls.begin(), walls.end(),
                              [&](const ScreenPolygon& w) { return w.Contains(sx, sy); });
    }
  return static_cast<double>(visible) / inside;
}

// The light's energy in the frame of `proto` from the origin camera (box2): the frame less the
// frame without the light (the walls' grey is the same in both), and the walls as projected.
void RenderLightBehindWalls(const v1::Scene& proto, double& light, FrameGeometry& geo) {
  auto scene = BuildScene(proto);
  ASSERT_TRUE(scene.ok()) << scene.status();
  const Camera camera = OriginCamera();
  const RenderSettings settings = Settings(AntiAliasing::kBox2);
  auto frame = RenderFrame(*scene, camera, settings);
  ASSERT_TRUE(frame.ok());
  v1::Scene dark = proto;
  dark.clear_lights();
  auto dark_scene = BuildScene(dark);
  ASSERT_TRUE(dark_scene.ok());
  auto without = RenderFrame(*dark_scene, camera, settings);
  ASSERT_TRUE(without.ok());
  light = RedSum(frame->image) - RedSum(without->image);
  geo = ProjectScene(*scene, camera, kWidth, kHeight, 2);
}

TEST(LightPass, ALightPartlyBehindAnEdgeKeepsItsVisibleShare) {
  // A light 40 m ahead, its footprint widened to 6 pixels, behind a wall 20 m ahead whose
  // slanted left edge crosses the footprint at several offsets.
  for (double shift : {-0.4, -0.15, 0.0, 0.2, 0.45}) {
    v1::Scene proto = OneLight(0, 0, -40, 30);
    proto.mutable_light_settings()->set_min_size_px(6);
    v1::Mesh& wall = *proto.add_meshes();
    wall.set_id("wall");
    v1::Polygon& quad = *wall.add_polygons();
    // Screen x of the light's centre is 32; at 20 m a pixel is pixel_m metres.
    const double pixel_m = 2 * std::tan(Radians(30)) / kHeight * 20;
    const double x0 = shift * 3 * pixel_m;
    for (auto [x, y] : {std::pair{x0 - 0.3 * pixel_m * 4, -10.0},
                        {10.0, -10.0},
                        {10.0, 10.0},
                        {x0 + 0.3 * pixel_m * 4, 10.0}}) {
      v1::Vec3& v = *quad.add_vertices();
      v.set_x(x);
      v.set_y(y * pixel_m);
      v.set_z(-20);
    }
    double light = 0;
    FrameGeometry geo;
    ASSERT_NO_FATAL_FAILURE(RenderLightBehindWalls(proto, light, geo));
    ASSERT_EQ(geo.polygons.size(), 1u);
    const double share = VisibleShareBySampling(geo.polygons, kWidth / 2.0, kHeight / 2.0, 3);
    const double want = AnalyticEnergy({0, 0, -40}, 30) * share;
    EXPECT_NEAR(light, want, 2e-3 * AnalyticEnergy({0, 0, -40}, 30)) << "shift " << shift;
    EXPECT_GT(share, 0.05);
    EXPECT_LT(share, 0.95);
  }
}

// Behind a comb of thin slats, a few or so many that cutting the footprint by their outlines
// would leave too many pieces (and each cell is resolved among them instead), a light keeps the
// share of its footprint that sampling finds between them.
TEST(LightPass, ALightBehindACombOfSlatsKeepsItsVisibleShare) {
  const double pixel_m = 2 * std::tan(Radians(30)) / kHeight * 20;
  for (int slats : {3, 80}) {
    v1::Scene proto = OneLight(0, 0, -40, 30);
    proto.mutable_light_settings()->set_min_size_px(6);
    v1::Mesh& comb = *proto.add_meshes();
    comb.set_id("comb");
    // Slats across the footprint's 6 pixels, each covering 40 % of its share of the width,
    // slanted so that no edge runs along a cell's.
    const double pitch = 6.4 / slats * pixel_m;
    for (int k = 0; k < slats; ++k) {
      const double x0 = (-3.2 + 0.05) * pixel_m + k * pitch;
      v1::Polygon& quad = *comb.add_polygons();
      for (auto [x, y] : {std::pair{x0, -4.0},
                          {x0 + 0.4 * pitch, -4.0},
                          {x0 + 0.4 * pitch + 0.3 * pixel_m, 4.0},
                          {x0 + 0.3 * pixel_m, 4.0}}) {
        v1::Vec3& v = *quad.add_vertices();
        v.set_x(x);
        v.set_y(y * pixel_m);
        v.set_z(-20);
      }
    }
    double light = 0;
    FrameGeometry geo;
    ASSERT_NO_FATAL_FAILURE(RenderLightBehindWalls(proto, light, geo));
    ASSERT_EQ(geo.polygons.size(), static_cast<size_t>(slats));
    const double share = VisibleShareBySampling(geo.polygons, kWidth / 2.0, kHeight / 2.0, 3);
    const double want = AnalyticEnergy({0, 0, -40}, 30) * share;
    EXPECT_NEAR(light, want, 2e-3 * AnalyticEnergy({0, 0, -40}, 30)) << slats << " slats";
    EXPECT_GT(share, 0.4);
    EXPECT_LT(share, 0.8);
  }
}

// Sliding behind a wall's edge, a light's energy falls monotonically and continuously: no step
// larger than the change of the covered share between frames.
TEST(LightPass, ALightSlidingBehindAnEdgeDimsContinuously) {
  const double pixel_m = 2 * std::tan(Radians(30)) / kHeight * 40;
  v1::Scene proto = OneLight(0, 0, -40, 30);
  proto.mutable_light_settings()->set_min_size_px(3);
  v1::Mesh& wall = *proto.add_meshes();
  wall.set_id("wall");
  v1::Polygon& quad = *wall.add_polygons();
  for (auto [x, y] : {std::pair{0.0, -10.0}, {10.0, -10.0}, {10.0, 10.0}, {0.0, 10.0}}) {
    v1::Vec3& v = *quad.add_vertices();
    v.set_x(x);
    v.set_y(y);
    v.set_z(-20);
  }
  v1::Scene dark = proto;
  dark.clear_lights();
  const double dark_sum = RedSum(Render(dark, OriginCamera(), AntiAliasing::kTent2));
  double last = -1;
  const double full = AnalyticEnergy({0, 0, -40}, 30);
  for (int step = 0; step <= 80; ++step) {
    // The light from 2 pixels left of the edge's line of sight to 2 pixels right of it.
    const double x = (-2 + step * 0.05) * pixel_m;
    proto.mutable_lights(0)->mutable_position()->set_x(x);
    const double energy = RedSum(Render(proto, OriginCamera(), AntiAliasing::kTent2)) - dark_sum;
    if (last >= 0) {
      EXPECT_LE(energy, last + 1e-6 * full) << "step " << step;
      // A 3-pixel footprint moving 0.05 pixel changes its covered share by at most 0.05 x its
      // height / its area (about 0.02): never a pop.
      EXPECT_LT(last - energy, 0.03 * full) << "step " << step;
    }
    last = energy;
  }
  EXPECT_LT(last, 1e-6 * full);  // wholly behind at the end
}

TEST(LightPass, FogAttenuatesByItsTransmissionAndTheHaloCarriesTheScatteredShare) {
  const Vec3 p{0.5, 0.2, -50};
  const double density = 0.02, d = Length(p), transmission = std::exp(-density * d);
  v1::Scene proto = OneLight(p.x, p.y, p.z, 30);
  proto.mutable_fog()->set_density(density);
  // The fog's colour over the empty sky is the frame's background: taken away.
  v1::Scene dark = proto;
  dark.clear_lights();
  const double background = RedSum(Render(dark, OriginCamera(), AntiAliasing::kBox2));
  const double energy = RedSum(Render(proto, OriginCamera(), AntiAliasing::kBox2)) - background;
  const double want =
      AnalyticEnergy(p, 30) * (transmission + (1 - transmission) * kHaloForwardShare);
  EXPECT_NEAR(energy, want, 1e-5 * want);
}

TEST(LightPass, AGroupUpdateEqualsAFreshBuildOfTheChangedScene) {
  v1::Scene proto = OneLight(0.3, 0.1, -30, 20);
  auto scene = BuildScene(proto);
  ASSERT_TRUE(scene.ok());
  v1::SceneUpdate update;
  v1::LightGroupUpdate& g = *update.add_light_groups();
  g.set_group("lamps");
  g.mutable_intensity_scale()->set_value(0.3);
  ASSERT_TRUE(ApplySceneUpdate(update, &*scene).ok());
  const RenderSettings settings = Settings(AntiAliasing::kBox2);
  auto updated = RenderFrame(*scene, OriginCamera(), settings);
  v1::Scene changed = proto;
  changed.mutable_lights(0)->set_intensity_cd(20 * 0.3);
  const Image fresh = Render(changed, OriginCamera(), AntiAliasing::kBox2);
  ASSERT_TRUE(updated.ok());
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x)
      ASSERT_NEAR(updated->image.at(x, y).r, fresh.at(x, y).r, 1e-6) << x << "," << y;
  // Switched off, nothing of it shows.
  g.clear_intensity_scale();
  g.set_visibility(v1::VISIBILITY_HIDDEN);
  ASSERT_TRUE(ApplySceneUpdate(update, &*scene).ok());
  auto off = RenderFrame(*scene, OriginCamera(), settings);
  ASSERT_TRUE(off.ok());
  EXPECT_EQ(RedSum(off->image), 0);
  // An unknown group is refused, naming it.
  g.set_group("nope");
  const absl::Status refused = ApplySceneUpdate(update, &*scene);
  EXPECT_TRUE(absl::IsInvalidArgument(refused)) << refused;
  EXPECT_NE(refused.message().find("update.light_groups[0]: no light group 'nope'"),
            std::string::npos)
      << refused;
}

TEST(LightPass, FlashingLightsAreOnForTheirOnTimeOfEachPeriod) {
  v1::Scene proto = OneLight(0, 0, -30, 20);
  v1::LightFlash& flash = *proto.mutable_lights(0)->mutable_flash();
  flash.set_period_s(1.0);
  flash.set_on_s(0.1);
  flash.set_phase_s(0.25);
  for (auto [t, on] : {std::pair{0.0, false},
                       {0.25, true},
                       {0.34, true},
                       {0.36, false},
                       {1.3, true},
                       {-0.7, true},
                       {-0.6, false}}) {
    const double sum = RedSum(Render(proto, OriginCamera(), AntiAliasing::kBox2, t));
    EXPECT_EQ(sum > 0, on) << "t " << t;
  }
}

// A light standing on the ground (0.3 m above it), seen at a grazing angle from 2 km: the ground in
// front of it covers the lower half of its footprint on the screen, but the view ray meets the
// light before the ground, and a footprint is hidden only by what is nearer where the light is.
TEST(LightPass, TheGroundALightStandsOnDoesNotHideIt) {
  v1::Scene proto = OneLight(0, 0.3, -2000, 10000);
  v1::Mesh& ground = *proto.add_meshes();
  ground.set_id("ground");
  v1::Polygon& quad = *ground.add_polygons();
  for (auto [x, z] : {std::pair{-100.0, 0.0}, {100.0, 0.0}, {100.0, -5000.0}, {-100.0, -5000.0}}) {
    v1::Vec3& v = *quad.add_vertices();
    v.set_x(x);
    v.set_z(z);
  }
  Camera camera = OriginCamera();
  camera.position = {0, 100, 0};
  camera.pitch_deg = -std::atan(99.7 / 2000) * 180 / kPi;  // looking at the light
  v1::Scene dark = proto;
  dark.clear_lights();
  const double energy = RedSum(Render(proto, camera, AntiAliasing::kBox2)) -
                        RedSum(Render(dark, camera, AntiAliasing::kBox2));
  const Vec3 p = camera.Orientation().Transposed() * (Vec3{0, 0.3, -2000} - camera.position);
  EXPECT_NEAR(energy, AnalyticEnergy(p, 10000), 1e-4 * AnalyticEnergy(p, 10000));
}

TEST(LightPass, TheLobeFollowsItsFormula) {
  PointLight light;
  light.intensity_cd = 100;
  light.directional = true;
  const double h = Radians(10), v = Radians(5);
  light.lobe = {{0, 0, 1}, std::tan(h), std::tan(v), 0.05};
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> angle(-0.3, 0.3);
  for (int trial = 0; trial < 200; ++trial) {
    // A direction at horizontal angle a and vertical angle b from the axis (+z).
    const double a = angle(rng), b = angle(rng);
    const Vec3 dir = Normalize({std::tan(a), std::tan(b), 1});
    // The frame: right = axis x up = (0,0,1) x (0,1,0) = (-1, 0, 0); over = right x axis.
    const double x = -dir.x / dir.z, y = dir.y / dir.z;
    const double r2 = (x / std::tan(h)) * (x / std::tan(h)) + (y / std::tan(v)) * (y / std::tan(v));
    const double want = 100 * std::max(0.05, 1 - r2);
    EXPECT_NEAR(LightIntensityTowards(light, dir, 0, {}), want, 1e-9) << a << ", " << b;
  }
  EXPECT_NEAR(LightIntensityTowards(light, {0, 0, -1}, 0, {}), 5, 1e-12);  // behind: the back
}

TEST(LightPass, BadLightsAreRefusedNamingTheField) {
  auto error = [](const v1::Scene& proto) {
    return std::string(BuildScene(proto).status().message());
  };
  v1::Scene nan = OneLight(NAN, 0, -10, 1);
  EXPECT_EQ(error(nan), "lights[0].position: coordinate is NaN or infinite");
  v1::Scene negative = OneLight(0, 0, -10, -3);
  EXPECT_EQ(error(negative), "lights[0].intensity_cd: must be > 0, is -3");
  v1::Scene axis = OneLight(0, 0, -10, 1);
  axis.mutable_lights(0)->mutable_lobe()->set_horizontal_deg(5);
  axis.mutable_lights(0)->mutable_lobe()->set_vertical_deg(5);
  EXPECT_EQ(error(axis), "lights[0].lobe.axis: must be a finite non-zero direction");
  v1::Scene row;
  v1::LightRow& r = *row.add_light_rows();
  r.mutable_end()->set_z(-1e6);
  r.set_spacing_m(0.01);
  r.mutable_light()->set_intensity_cd(1);
  SceneBuildOptions options;
  options.limits.lights = 1000000;
  const absl::Status huge = BuildScene(row, options).status();
  EXPECT_TRUE(absl::IsInvalidArgument(huge));
  EXPECT_NE(huge.message().find("light_rows[0]: spacing_m 0.01 over 1e+06 m makes"),
            std::string::npos)
      << huge;
  // With no limit (0) too: a row 3e23 m long (the fuzzer's) makes more lights than a row holds.
  r.mutable_end()->set_z(-3e23);
  r.set_spacing_m(60);
  options.limits.lights = 0;
  const absl::Status endless = BuildScene(row, options).status();
  EXPECT_TRUE(absl::IsInvalidArgument(endless));
  EXPECT_NE(endless.message().find("above the limit of 4294967295 lights a row"), std::string::npos)
      << endless;
  EXPECT_FALSE(CountSceneLights(row, 0).ok());
  r.set_spacing_m(0);
  EXPECT_EQ(error(row), "light_rows[0].spacing_m: must be > 0 (or give count), is 0");
  v1::Scene object = OneLight(0, 0, -10, 1);
  object.mutable_lights(0)->set_object("jet");
  EXPECT_EQ(error(object), "lights[0].object: 'jet' is not a named object of the scene");
}

}  // namespace
}  // namespace aperture
