// Spot lights (scene/spot_lights.h) against their photometric definition: a frame of a lit plane
// seen from above holds, at every pixel centre, albedo x exposure x surface_exposure / pi times
// E = I f(theta) cos(i) T(d) / d^2, with f 1 inside the inner cone, 0 outside the outer one and
// the smoothstep t^2 (3 - 2 t) between, all computed here from the pixel's ray and the plane; a
// lamp behind the seen side lights nothing; across a polygon's edge each side is shaded at the
// pixel centre and weighted by its exact area; a spot attached to an object and moved by a
// SceneUpdate gives the frame of a fresh load of the moved scene; bad input is refused naming the
// field.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "render/frame_renderer.h"
#include "scene/scene_builder.h"
#include "scene/scene_update.h"
#include "scene/spot_lights.h"

namespace aperture {
namespace {

constexpr int kWidth = 96, kHeight = 64;
constexpr double kCameraHeight = 40, kAlbedo = 0.8, kExposure = 0.01, kSurfaceExposure = 50;

void Set(v1::Vec3* v, double x, double y, double z) {
  v->set_x(x);
  v->set_y(y);
  v->set_z(z);
}

// A lit white-grey plane y = 0 of 400 m, no sun, no ambient, no sky: what shows is the spots'.
v1::Scene LitPlane() {
  v1::Scene scene;
  scene.set_name("lit plane");
  v1::Material& m = *scene.add_materials();
  m.set_id("concrete");
  m.mutable_base_color()->set_r(kAlbedo);
  m.mutable_base_color()->set_g(kAlbedo);
  m.mutable_base_color()->set_b(kAlbedo);
  v1::Mesh& mesh = *scene.add_meshes();
  mesh.set_id("ground");
  mesh.set_material_id("concrete");
  v1::Polygon& p = *mesh.add_polygons();
  for (auto [x, z] : {std::pair{-200.0, 200.0}, {200.0, 200.0}, {200.0, -200.0}, {-200.0, -200.0}})
    Set(p.add_vertices(), x, 0, z);
  scene.add_objects()->set_mesh_id("ground");
  scene.mutable_ambient();  // black
  scene.mutable_sun()->mutable_direction()->set_y(1);
  scene.mutable_sun()->mutable_color();  // black
  scene.mutable_light_settings()->set_exposure(kExposure);
  scene.mutable_light_settings()->set_surface_exposure(kSurfaceExposure);
  return scene;
}

v1::SpotLight* AddSpot(v1::Scene* scene, const Vec3& at, const Vec3& direction, double cd,
                       double inner_deg, double outer_deg) {
  v1::SpotLight* s = scene->add_spot_lights();
  Set(s->mutable_position(), at.x, at.y, at.z);
  Set(s->mutable_direction(), direction.x, direction.y, direction.z);
  s->set_intensity_cd(cd);
  s->set_inner_deg(inner_deg);
  s->set_outer_deg(outer_deg);
  return s;
}

// Straight down from kCameraHeight over the origin: image right is +x, image up is -z.
Camera DownCamera() {
  Camera camera;
  camera.position = {0, kCameraHeight, 0};
  camera.pitch_deg = -90;
  camera.vertical_fov_deg = 60;
  return camera;
}

// Where the ray through pixel centre (i + 0.5, j + 0.5) of DownCamera meets y = 0, and how far
// from the camera it is.
Vec3 GroundAt(int i, int j, double* view_distance) {
  const double tan_half = std::tan(30 * kPi / 180);
  const double tx = (2 * (i + 0.5) / kWidth - 1) * tan_half * kWidth / kHeight;
  const double ty = (1 - 2 * (j + 0.5) / kHeight) * tan_half;
  const Vec3 p{kCameraHeight * tx, 0, -kCameraHeight * ty};
  *view_distance = kCameraHeight * std::sqrt(1 + tx * tx + ty * ty);
  return p;
}

// The illuminance (lux) of a spot at a point of the plane y = 0 seen from above (normal +y),
// from the definition, and the cone fall-off written out.
double Illuminance(const Vec3& lamp, const Vec3& direction, double cd, double inner_deg,
                   double outer_deg, const Vec3& p, double fog_density) {
  const Vec3 to_lamp{lamp.x - p.x, lamp.y - p.y, lamp.z - p.z};
  const double d = std::sqrt(to_lamp.x * to_lamp.x + to_lamp.y * to_lamp.y + to_lamp.z * to_lamp.z);
  const double cos_i = to_lamp.y / d;
  if (cos_i <= 0) return 0;
  const double dl =
      std::sqrt(direction.x * direction.x + direction.y * direction.y + direction.z * direction.z);
  const double cos_theta =
      -(direction.x * to_lamp.x + direction.y * to_lamp.y + direction.z * to_lamp.z) / (dl * d);
  const double theta = std::acos(std::min(1.0, cos_theta)) * 180 / kPi;
  double f;
  if (theta <= inner_deg) {
    f = 1;
  } else if (theta >= outer_deg) {
    f = 0;
  } else {
    const double ci = std::cos(inner_deg * kPi / 180), co = std::cos(outer_deg * kPi / 180);
    const double t = (cos_theta - co) / (ci - co);
    f = t * t * (3 - 2 * t);
  }
  return cd * f * cos_i * std::exp(-fog_density * d) / (d * d);
}

Image Render(const v1::Scene& proto, bool light_points = false) {
  auto scene = BuildScene(proto);
  EXPECT_TRUE(scene.ok()) << scene.status();
  if (!scene.ok()) return Image();
  RenderSettings settings;
  settings.width = kWidth;
  settings.height = kHeight;
  settings.aa = AntiAliasing::kBox1;
  settings.threads = 1;
  settings.draw_light_points = light_points;
  auto frame = RenderFrame(*scene, DownCamera(), settings);
  EXPECT_TRUE(frame.ok()) << frame.status();
  return frame.ok() ? frame->image : Image();
}

// Every pixel of the frame against the definition; counts of pixels in the full beam, in the
// fall-off and dark are returned so that a test can ask that each was reached.
struct Counts {
  int full = 0, falloff = 0, dark = 0, wrong = 0;
};
Counts ExpectIlluminance(const v1::Scene& proto, double fog_density) {
  const Image image = Render(proto);
  Counts counts;
  const double per_lux = kAlbedo * kExposure * kSurfaceExposure / kPi;
  for (int j = 0; j < kHeight; ++j)
    for (int i = 0; i < kWidth; ++i) {
      double view = 0;
      const Vec3 p = GroundAt(i, j, &view);
      double want = 0;
      bool full = false, lit = false;
      for (const v1::SpotLight& s : proto.spot_lights()) {
        const Vec3 lamp{s.position().x(), s.position().y(), s.position().z()};
        const Vec3 dir{s.direction().x(), s.direction().y(), s.direction().z()};
        const double e =
            Illuminance(lamp, dir, s.intensity_cd(), s.inner_deg(), s.outer_deg(), p, fog_density);
        const double inverse_square = Illuminance(lamp, dir, s.intensity_cd(), 90, 90, p, 0) *
                                      std::exp(-fog_density * Length(lamp - p));
        if (e > 0) lit = true;
        if (e > 0 && std::abs(e - inverse_square) <= 1e-12 * e) full = true;
        want += e;
      }
      want *= per_lux * std::exp(-fog_density * view);  // seen through the fog (black)
      const double got = image.at(i, j).r;
      EXPECT_NEAR(got, want, 2e-6 + 2e-5 * want) << "pixel " << i << "," << j;
      if (std::abs(got - want) > 2e-6 + 2e-5 * want && ++counts.wrong > 5) return counts;
      if (full) {
        ++counts.full;
      } else if (lit) {
        ++counts.falloff;
      } else {
        ++counts.dark;
      }
    }
  return counts;
}

TEST(SpotLight, StraightDownGivesICosIOverDSquaredInsideTheConeAndNothingOutside) {
  v1::Scene proto = LitPlane();
  AddSpot(&proto, {3, 12, -4}, {0, -1, 0}, 20000, 20, 35);
  const Counts counts = ExpectIlluminance(proto, 0);
  EXPECT_GT(counts.full, 100);
  EXPECT_GT(counts.falloff, 100);
  EXPECT_GT(counts.dark, 100);
}

TEST(SpotLight, AGrazingBeamFallsOffBetweenItsConesByTheSmoothstep) {
  v1::Scene proto = LitPlane();
  // A landing light's beam, 6 m up, aimed 10 degrees down: it meets the plane obliquely.
  AddSpot(&proto, {-30, 6, 10}, {1, -std::tan(10 * kPi / 180), -0.3}, 200000, 4, 9);
  const Counts counts = ExpectIlluminance(proto, 0);
  EXPECT_GT(counts.full, 20);
  EXPECT_GT(counts.falloff, 20);
  EXPECT_GT(counts.dark, 100);
}

TEST(SpotLight, FogTakesItsTransmissionAlongTheBeamAndTheViewRay) {
  v1::Scene proto = LitPlane();
  proto.mutable_fog()->set_density(0.01);  // black fog
  AddSpot(&proto, {0, 15, 0}, {0.2, -1, 0.1}, 30000, 10, 25);
  AddSpot(&proto, {-20, 8, 10}, {-0.1, -1, 0}, 8000, 0, 30);  // inner 0: all fall-off
  const Counts counts = ExpectIlluminance(proto, 0.01);
  EXPECT_GT(counts.full, 10);
  EXPECT_GT(counts.falloff, 100);
}

TEST(SpotLight, ALampBelowThePlaneLightsNothingOfItsSeenSide) {
  v1::Scene proto = LitPlane();
  AddSpot(&proto, {0, -5, 0}, {0, 1, 0}, 20000, 20, 35);
  const Image image = Render(proto);
  for (const Rgba& p : image.texels()) ASSERT_EQ(p.r, 0);
}

TEST(SpotLight, ItsLampIsALightPointOfTheSameIntensityAimedAlongTheBeam) {
  v1::Scene proto = LitPlane();
  v1::SpotLight* s = AddSpot(&proto, {1, 2, 3}, {0, 0, -2}, 5000, 5, 12);
  s->set_group("landing");
  auto scene = BuildScene(proto);
  ASSERT_TRUE(scene.ok()) << scene.status();
  ASSERT_EQ(scene->lights.lights.size(), 1u);
  ASSERT_EQ(scene->lights.spots.size(), 1u);
  const PointLight& lamp = scene->lights.lights[0];
  EXPECT_EQ(lamp.intensity_cd, 5000);
  EXPECT_TRUE(lamp.directional);
  EXPECT_NEAR(lamp.lobe.axis.z, -1, 1e-12);
  EXPECT_NEAR(lamp.lobe.tan_horizontal, std::tan(12 * kPi / 180), 1e-12);
  EXPECT_EQ(lamp.group, scene->lights.spots[0].group);
  EXPECT_GE(lamp.group, 0);
}

// A jet carrying a landing light, its transform in the scene or given by an update.
v1::Scene WithJet(double x, double z, double yaw_deg, double pitch_deg) {
  v1::Scene proto = LitPlane();
  v1::Mesh& mesh = *proto.add_meshes();
  mesh.set_id("jet");
  mesh.set_material_id("concrete");
  v1::Polygon& p = *mesh.add_polygons();
  Set(p.add_vertices(), -1, 2, 0);
  Set(p.add_vertices(), 1, 2, 0);
  Set(p.add_vertices(), 0, 2, -3);
  v1::Object& jet = *proto.add_objects();
  jet.set_mesh_id("jet");
  jet.set_name("jet");
  Set(jet.mutable_transform()->mutable_translation(), x, 3, z);
  jet.mutable_transform()->set_yaw_deg(yaw_deg);
  jet.mutable_transform()->set_pitch_deg(pitch_deg);
  v1::SpotLight* s = AddSpot(&proto, {0.5, 1.5, -3}, {0, -0.2, -1}, 100000, 6, 14);
  s->set_object("jet");
  s->set_group("landing");
  return proto;
}

TEST(SpotLight, AnUpdateMovingItsObjectEqualsAFreshLoadOfTheMovedScene) {
  auto scene = BuildScene(WithJet(-10, 20, 0, 0));
  ASSERT_TRUE(scene.ok()) << scene.status();
  v1::SceneUpdate update;
  v1::ObjectUpdate& o = *update.add_objects();
  o.set_name("jet");
  Set(o.mutable_transform()->mutable_translation(), 5, 3, 15);
  o.mutable_transform()->set_yaw_deg(25);
  o.mutable_transform()->set_pitch_deg(-3);
  ASSERT_TRUE(ApplySceneUpdate(update, &*scene).ok());
  RenderSettings settings;
  settings.width = kWidth;
  settings.height = kHeight;
  settings.aa = AntiAliasing::kTent2;
  settings.threads = 1;
  auto moved = RenderFrame(*scene, DownCamera(), settings);
  ASSERT_TRUE(moved.ok()) << moved.status();
  auto fresh_scene = BuildScene(WithJet(5, 15, 25, -3));
  ASSERT_TRUE(fresh_scene.ok());
  auto fresh = RenderFrame(*fresh_scene, DownCamera(), settings);
  ASSERT_TRUE(fresh.ok());
  double lit = 0;
  for (int j = 0; j < kHeight; ++j)
    for (int i = 0; i < kWidth; ++i) {
      ASSERT_EQ(moved->image.at(i, j).r, fresh->image.at(i, j).r) << i << "," << j;
      ASSERT_EQ(moved->image.at(i, j).b, fresh->image.at(i, j).b) << i << "," << j;
      lit += moved->image.at(i, j).r;
    }
  EXPECT_GT(lit, 1);  // the beam reaches the ground in the frame
  // Where it stood before, its light is gone: the frames before and after differ.
  auto before_scene = BuildScene(WithJet(-10, 20, 0, 0));
  ASSERT_TRUE(before_scene.ok());
  auto before = RenderFrame(*before_scene, DownCamera(), settings);
  ASSERT_TRUE(before.ok());
  double differ = 0;
  for (int j = 0; j < kHeight; ++j)
    for (int i = 0; i < kWidth; ++i)
      differ += std::abs(before->image.at(i, j).r - moved->image.at(i, j).r);
  EXPECT_GT(differ, 1);
  // Its group switched off, the spot lights nothing and its lamp shows nowhere.
  v1::SceneUpdate off;
  v1::LightGroupUpdate& g = *off.add_light_groups();
  g.set_group("landing");
  g.set_visibility(v1::VISIBILITY_HIDDEN);
  ASSERT_TRUE(ApplySceneUpdate(off, &*scene).ok());
  auto dark = RenderFrame(*scene, DownCamera(), settings);
  ASSERT_TRUE(dark.ok());
  for (const Rgba& p : dark->image.texels()) ASSERT_EQ(p.r, 0);
}

// The overlap of [a0, a1] with [b0, b1].
double Overlap(double a0, double a1, double b0, double b1) {
  return std::max(0.0, std::min(a1, b1) - std::max(a0, b0));
}

TEST(SpotLight, EdgesStayExactTheBeamShadesEachSideAtThePixelCentre) {
  // A paint square 1 m above the plane under a lamp straight down: each pixel is the exact area
  // of the square in it times the square's light at the pixel centre, plus the rest of the pixel
  // times the ground's (the box filter's exact coverage, seed 002's colour per aperture).
  constexpr double kPaint = 0.3, kLift = 1;
  constexpr double x0 = -2.37, x1 = 3.11, z0 = -1.73, z1 = 2.64;
  v1::Scene proto = LitPlane();
  v1::Material& m = *proto.add_materials();
  m.set_id("paint");
  m.mutable_base_color()->set_r(kPaint);
  m.mutable_base_color()->set_g(kPaint);
  m.mutable_base_color()->set_b(kPaint);
  v1::Mesh& mesh = *proto.add_meshes();
  mesh.set_id("square");
  mesh.set_material_id("paint");
  v1::Polygon& p = *mesh.add_polygons();
  for (auto [x, z] : {std::pair{x0, z1}, {x1, z1}, {x1, z0}, {x0, z0}})
    Set(p.add_vertices(), x, kLift, z);
  proto.add_objects()->set_mesh_id("square");
  const Vec3 lamp{0.4, 12, 0.3}, down{0, -1, 0};
  AddSpot(&proto, lamp, down, 20000, 25, 40);
  const Image image = Render(proto);

  const double tan_half = std::tan(30 * kPi / 180), aspect = double{kWidth} / kHeight;
  const double depth = kCameraHeight - kLift;
  auto screen_x = [&](double x) { return (x / depth / (tan_half * aspect) + 1) * kWidth / 2; };
  auto screen_y = [&](double z) { return (1 + z / depth / tan_half) * kHeight / 2; };
  const double sx0 = screen_x(x0), sx1 = screen_x(x1), sy0 = screen_y(z0), sy1 = screen_y(z1);
  const double per_lux = kExposure * kSurfaceExposure / kPi;
  int edges = 0;
  for (int j = 0; j < kHeight; ++j)
    for (int i = 0; i < kWidth; ++i) {
      const double area = Overlap(i, i + 1, sx0, sx1) * Overlap(j, j + 1, sy0, sy1);
      double view = 0;
      const Vec3 ground = GroundAt(i, j, &view);
      const Vec3 on_square = ground * (depth / kCameraHeight);  // the same ray at y = kLift
      const double ground_light = Illuminance(lamp, down, 20000, 25, 40, ground, 0);
      const double square_light =
          Illuminance(lamp - Vec3{0, kLift, 0}, down, 20000, 25, 40, on_square, 0);
      const double want =
          per_lux * (area * kPaint * square_light + (1 - area) * kAlbedo * ground_light);
      ASSERT_NEAR(image.at(i, j).r, want, 2e-6 + 2e-5 * want) << "pixel " << i << "," << j;
      if (area > 0.05 && area < 0.95) ++edges;
    }
  EXPECT_GT(edges, 20);
}

// The error of building `proto`, which must be refused.
std::string Refusal(const v1::Scene& proto) {
  auto scene = BuildScene(proto);
  EXPECT_FALSE(scene.ok());
  return scene.ok() ? "" : std::string(scene.status().message());
}

TEST(SpotLight, BadInputIsRefusedNamingTheField) {
  auto with = [](auto change) {
    v1::Scene proto = LitPlane();
    AddSpot(&proto, {0, 5, 0}, {0, -1, 0}, 1000, 5, 10);
    AddSpot(&proto, {0, 5, 0}, {0, -1, 0}, 1000, 5, 10);
    change(*proto.mutable_spot_lights(1));
    return proto;
  };
  auto expect = [&](const v1::Scene& proto, const std::string& field) {
    const std::string message = Refusal(proto);
    EXPECT_EQ(message.rfind(field, 0), 0u) << message;
  };
  expect(with([](v1::SpotLight& s) { s.mutable_position()->set_y(NAN); }),
         "spot_lights[1].position");
  expect(with([](v1::SpotLight& s) { s.set_intensity_cd(-5); }), "spot_lights[1].intensity_cd");
  expect(with([](v1::SpotLight& s) { s.set_intensity_cd(NAN); }), "spot_lights[1].intensity_cd");
  expect(with([](v1::SpotLight& s) { s.set_intensity_cd(0); }), "spot_lights[1].intensity_cd");
  expect(with([](v1::SpotLight& s) { s.clear_direction(); }), "spot_lights[1].direction");
  expect(with([](v1::SpotLight& s) { s.mutable_direction()->set_x(INFINITY); }),
         "spot_lights[1].direction");
  expect(with([](v1::SpotLight& s) { s.set_inner_deg(12); }), "spot_lights[1].inner_deg");
  expect(with([](v1::SpotLight& s) { s.set_inner_deg(-1); }), "spot_lights[1].inner_deg");
  expect(with([](v1::SpotLight& s) { s.set_outer_deg(90); }), "spot_lights[1].outer_deg");
  expect(with([](v1::SpotLight& s) { s.set_outer_deg(NAN); }), "spot_lights[1].outer_deg");
  expect(with([](v1::SpotLight& s) { s.mutable_color()->set_g(-1); }), "spot_lights[1].color");
  expect(with([](v1::SpotLight& s) { s.set_radius_m(-1); }), "spot_lights[1].radius_m");
  expect(with([](v1::SpotLight& s) { s.set_object("nobody"); }), "spot_lights[1].object");
  v1::Scene exposure = with([](v1::SpotLight&) {});
  exposure.mutable_light_settings()->set_surface_exposure(-2);
  expect(exposure, "light_settings.surface_exposure");
  // One above the budget is refused before anything is built; the budget itself is not.
  v1::Scene many = LitPlane();
  for (int i = 0; i < kMaxSpotLights; ++i) AddSpot(&many, {0, 5, 0}, {0, -1, 0}, 1000, 5, 10);
  EXPECT_TRUE(BuildScene(many).ok());
  AddSpot(&many, {0, 5, 0}, {0, -1, 0}, 1000, 5, 10);
  const std::string over = Refusal(many);
  EXPECT_EQ(over.rfind("spot_lights: the scene has 17, above the budget of 16", 0), 0u) << over;
}

}  // namespace
}  // namespace aperture
