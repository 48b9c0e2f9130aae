// Per-frame updates: an updated scene holds exactly what a fresh build of the moved
// scene holds, bad updates change nothing, and merged updates equal the updates applied in turn.
#include "scene/scene_update.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "absl/strings/str_cat.h"
#include "render/frame_renderer.h"
#include "scene/demo_scene.h"
#include "scene/scene_builder.h"

namespace aperture {
namespace {

v1::Object* Aircraft(v1::Scene& proto) {
  for (v1::Object& o : *proto.mutable_objects())
    if (o.name() == kDemoAircraft) return &o;
  return nullptr;
}

bool SamePolygon(const ScenePolygon& a, const ScenePolygon& b) {
  if (a.vertices.size() != b.vertices.size() || a.material != b.material) return false;
  for (size_t i = 0; i < a.vertices.size(); ++i)
    if (!(a.vertices[i] == b.vertices[i])) return false;
  const TextureMapping &ma = a.mapping, &mb = b.mapping;
  return a.normal == b.normal && ma.su == mb.su && ma.sv == mb.sv && ma.u0 == mb.u0 &&
         ma.v0 == mb.v0;
}

// Bit for bit: polygons, named objects' ranges and the environment.
void ExpectSameScene(const Scene& a, const Scene& b) {
  ASSERT_EQ(a.polygons.size(), b.polygons.size());
  for (size_t i = 0; i < a.polygons.size(); ++i)
    ASSERT_TRUE(SamePolygon(a.polygons[i], b.polygons[i])) << "polygon " << i;
  ASSERT_EQ(a.objects.size(), b.objects.size());
  for (size_t i = 0; i < a.objects.size(); ++i) {
    EXPECT_EQ(a.objects[i].first, b.objects[i].first);
    EXPECT_EQ(a.objects[i].count, b.objects[i].count);
    EXPECT_EQ(a.objects[i].visible, b.objects[i].visible);
  }
  EXPECT_TRUE(a.sun_direction == b.sun_direction);
  EXPECT_EQ(a.fog_density, b.fog_density);
  EXPECT_EQ(std::memcmp(&a.sky, &b.sky, sizeof(Rgba)), 0);
  EXPECT_EQ(std::memcmp(&a.fog_color, &b.fog_color, sizeof(Rgba)), 0);
  EXPECT_EQ(std::memcmp(&a.ambient, &b.ambient, sizeof(Rgba)), 0);
  EXPECT_EQ(std::memcmp(&a.sun_color, &b.sun_color, sizeof(Rgba)), 0);
}

Scene Build(const v1::Scene& proto) {
  auto scene = BuildScene(proto);
  EXPECT_TRUE(scene.ok()) << scene.status();
  return scene.ok() ? *std::move(scene) : Scene{};
}

v1::Transform Moved() {
  v1::Transform t;
  t.mutable_translation()->set_x(-30.5);
  t.mutable_translation()->set_y(2);
  t.mutable_translation()->set_z(-40.25);
  t.set_yaw_deg(33);
  t.set_pitch_deg(4);
  t.set_roll_deg(-7);
  t.mutable_scale()->set_x(1.5);
  t.mutable_scale()->set_y(1.25);
  t.mutable_scale()->set_z(0.75);
  return t;
}

TEST(SceneUpdate, DemoObjectsStandWhereTheMeshesAlone) {
  // The demo lists every mesh as an object (so the aircraft can move): placed by the identity,
  // the rest of the airfield is the polygons the meshes alone make, bit for bit.
  v1::Scene with_objects = MakeDemoScene();
  Aircraft(with_objects)->set_hidden(true);
  v1::Scene meshes_only = MakeDemoScene();
  meshes_only.clear_objects();
  meshes_only.mutable_meshes()->RemoveLast();  // the aircraft
  const Scene a = Build(with_objects), b = Build(meshes_only);
  ASSERT_EQ(a.polygons.size(), b.polygons.size());
  for (size_t i = 0; i < a.polygons.size(); ++i)
    ASSERT_TRUE(SamePolygon(a.polygons[i], b.polygons[i])) << "polygon " << i;
}

TEST(SceneUpdate, MovedObjectEqualsAFreshBuildOfTheMovedScene) {
  v1::Scene proto = MakeDemoScene();
  Scene live = Build(proto);
  v1::SceneUpdate update;
  v1::ObjectUpdate* o = update.add_objects();
  o->set_name(kDemoAircraft);
  *o->mutable_transform() = Moved();
  ASSERT_TRUE(ApplySceneUpdate(update, &live).ok());
  *Aircraft(proto)->mutable_transform() = Moved();
  const Scene fresh = Build(proto);
  ExpectSameScene(live, fresh);

  // And so are the pixels (the aircraft fills part of this view).
  Camera camera = DemoCamera();
  RenderSettings settings;
  settings.width = 160;
  settings.height = 90;
  settings.shading.override_filter = true;
  settings.shading.filter = FilterMode::kTrilinear;
  settings.threads = 1;
  camera.position = {0, 10, 120};
  auto a = RenderFrame(live, camera, settings), b = RenderFrame(fresh, camera, settings);
  ASSERT_TRUE(a.ok() && b.ok());
  EXPECT_EQ(std::memcmp(a->image.texels().data(), b->image.texels().data(),
                        a->image.texels().size_bytes()),
            0);
  // The move is visible: the same view of the unmoved scene differs.
  auto before = RenderFrame(Build(MakeDemoScene()), camera, settings);
  ASSERT_TRUE(before.ok());
  EXPECT_NE(std::memcmp(a->image.texels().data(), before->image.texels().data(),
                        a->image.texels().size_bytes()),
            0);
}

TEST(SceneUpdate, HideAndShowEqualFreshBuilds) {
  v1::Scene proto = MakeDemoScene();
  Scene live = Build(proto);
  const Scene original = live;
  v1::SceneUpdate hide;
  hide.add_objects()->set_name(kDemoAircraft);
  hide.mutable_objects(0)->set_visibility(v1::VISIBILITY_HIDDEN);
  ASSERT_TRUE(ApplySceneUpdate(hide, &live).ok());
  Aircraft(proto)->set_hidden(true);
  ExpectSameScene(live, Build(proto));
  EXPECT_LT(live.polygons.size(), original.polygons.size());

  // Moved while hidden, then shown: where it was moved to.
  v1::SceneUpdate move;
  move.add_objects()->set_name(kDemoAircraft);
  *move.mutable_objects(0)->mutable_transform() = Moved();
  ASSERT_TRUE(ApplySceneUpdate(move, &live).ok());
  ExpectSameScene(live, Build(proto));
  v1::SceneUpdate show;
  show.add_objects()->set_name(kDemoAircraft);
  show.mutable_objects(0)->set_visibility(v1::VISIBILITY_SHOWN);
  ASSERT_TRUE(ApplySceneUpdate(show, &live).ok());
  Aircraft(proto)->set_hidden(false);
  *Aircraft(proto)->mutable_transform() = Moved();
  ExpectSameScene(live, Build(proto));
}

// Two named objects around an unnamed one: ranges shift when the first one's count changes.
TEST(SceneUpdate, RangesOfLaterObjectsFollowAHiddenObject) {
  v1::Scene proto;
  v1::Mesh* mesh = proto.add_meshes();
  mesh->set_id("l");
  v1::Polygon* p = mesh->add_polygons();  // an L: concave, triangulated into 4 triangles
  for (const auto& [x, z] :
       std::vector<std::pair<double, double>>{{0, 0}, {2, 0}, {2, -1}, {1, -1}, {1, -2}, {0, -2}}) {
    v1::Vec3* v = p->add_vertices();
    v->set_x(x), v->set_z(z);
  }
  for (const char* name : {"a", "", "b"}) {
    v1::Object* o = proto.add_objects();
    o->set_mesh_id("l");
    o->set_name(name);
  }
  proto.mutable_objects(1)->mutable_transform()->mutable_translation()->set_x(5);
  proto.mutable_objects(2)->mutable_transform()->mutable_translation()->set_x(10);
  Scene live = Build(proto);
  ASSERT_EQ(live.objects.size(), 2u);
  EXPECT_EQ(live.objects[1].first, 8u);
  v1::SceneUpdate update;
  update.add_objects()->set_name("a");
  update.mutable_objects(0)->set_visibility(v1::VISIBILITY_HIDDEN);
  update.add_objects()->set_name("b");
  // The transform replaces the object's whole transform.
  update.mutable_objects(1)->mutable_transform()->set_yaw_deg(90);
  ASSERT_TRUE(ApplySceneUpdate(update, &live).ok());
  proto.mutable_objects(0)->set_hidden(true);
  proto.mutable_objects(2)->mutable_transform()->mutable_translation()->set_x(0);
  proto.mutable_objects(2)->mutable_transform()->set_yaw_deg(90);
  ExpectSameScene(live, Build(proto));
  EXPECT_EQ(live.objects[1].first, 4u);
}

TEST(SceneUpdate, EnvironmentEqualsAFreshBuild) {
  v1::Scene proto = MakeDemoScene();
  Scene live = Build(proto);
  v1::SceneUpdate update;
  update.mutable_sun()->mutable_direction()->set_x(-1);
  update.mutable_sun()->mutable_direction()->set_y(0.3);
  update.mutable_sun()->mutable_color()->set_r(1);
  update.mutable_ambient()->set_b(0.5f);
  update.mutable_fog()->set_visibility(800);
  update.mutable_fog()->mutable_color()->set_g(0.7f);
  update.mutable_sky()->set_r(0.2f);
  ASSERT_TRUE(ApplySceneUpdate(update, &live).ok());
  *proto.mutable_sun() = update.sun();
  *proto.mutable_ambient() = update.ambient();
  *proto.mutable_fog() = update.fog();
  *proto.mutable_sky() = update.sky();
  ExpectSameScene(live, Build(proto));
  // Visibility is where contrast falls to 5 %.
  EXPECT_NEAR(std::exp(-live.fog_density * 800), 0.05, 1e-12);
}

TEST(SceneUpdate, BadUpdatesNameTheFieldAndChangeNothing) {
  const Scene original = Build(MakeDemoScene());
  struct Case {
    const char* what;
    v1::SceneUpdate update;
    const char* message;
  };
  std::vector<Case> cases;
  auto object = [](const char* name) {
    v1::SceneUpdate u;
    v1::ObjectUpdate* o = u.add_objects();
    o->set_name(kDemoAircraft);
    *o->mutable_transform() = Moved();  // a valid first entry: must not be applied either
    u.add_objects()->set_name(name);
    return u;
  };
  cases.push_back({"unknown name", object("glider"), "update.objects[1] ('glider'): no object"});
  cases.push_back({"NaN yaw", object(kDemoAircraft), "transform angles are not finite"});
  cases.back().update.mutable_objects(1)->mutable_transform()->set_yaw_deg(std::nan(""));
  cases.push_back({"zero scale", object(kDemoAircraft), "scale must be finite and non-zero"});
  cases.back().update.mutable_objects(1)->mutable_transform()->mutable_scale()->set_x(0);
  cases.push_back({"bad visibility", object(kDemoAircraft), "visibility has unknown value 7"});
  cases.back().update.mutable_objects(1)->set_visibility(static_cast<v1::Visibility>(7));
  cases.push_back({"both fog", object(kDemoAircraft), "update.fog: set density or visibility"});
  cases.back().update.mutable_objects()->RemoveLast();
  cases.back().update.mutable_fog()->set_density(0.01);
  cases.back().update.mutable_fog()->set_visibility(100);
  cases.push_back({"negative sky", object(kDemoAircraft), "update.sky: colour components"});
  cases.back().update.mutable_objects()->RemoveLast();
  cases.back().update.mutable_sky()->set_r(-1);
  for (const Case& c : cases) {
    Scene live = original;
    const absl::Status check = CheckSceneUpdate(live, c.update);
    const absl::Status apply = ApplySceneUpdate(c.update, &live);
    EXPECT_TRUE(absl::IsInvalidArgument(apply)) << c.what << ": " << apply;
    EXPECT_EQ(check, apply) << c.what;
    EXPECT_NE(apply.message().find(c.message), std::string::npos) << c.what << ": " << apply;
    ExpectSameScene(live, original);
  }
}

TEST(SceneUpdate, MergedUpdatesEqualTheUpdatesInTurn) {
  const Scene original = Build(MakeDemoScene());
  v1::SceneUpdate first, second;
  first.add_objects()->set_name(kDemoAircraft);
  *first.mutable_objects(0)->mutable_transform() = Moved();
  first.mutable_fog()->set_density(0.002);
  second.add_objects()->set_name(kDemoAircraft);
  second.mutable_objects(0)->set_visibility(v1::VISIBILITY_HIDDEN);
  second.mutable_sky()->set_g(0.1f);
  Scene in_turn = original;
  ASSERT_TRUE(ApplySceneUpdate(first, &in_turn).ok());
  ASSERT_TRUE(ApplySceneUpdate(second, &in_turn).ok());
  v1::SceneUpdate merged = first;
  MergeSceneUpdate(second, &merged);
  EXPECT_EQ(merged.objects_size(), 1);  // one entry per object however many frames merge
  Scene at_once = original;
  ASSERT_TRUE(ApplySceneUpdate(merged, &at_once).ok());
  ExpectSameScene(at_once, in_turn);
  EXPECT_EQ(at_once.objects.back().transform.translation().x(), -30.5);
}

// Many named objects of one L-shaped mesh (4 triangles), every third one between two unnamed
// ones, some hidden as loaded: ranges of every size, shifted by what lies between them.
v1::Scene ManyNamedObjects(int objects) {
  v1::Scene proto;
  v1::Mesh* mesh = proto.add_meshes();
  mesh->set_id("l");
  v1::Polygon* p = mesh->add_polygons();
  for (const auto& [x, z] :
       std::vector<std::pair<double, double>>{{0, 0}, {2, 0}, {2, -1}, {1, -1}, {1, -2}, {0, -2}}) {
    v1::Vec3* v = p->add_vertices();
    v->set_x(x), v->set_z(z);
  }
  for (int i = 0; i < objects; ++i) {
    if (i % 3 == 0) proto.add_objects()->set_mesh_id("l");  // unnamed
    v1::Object* o = proto.add_objects();
    o->set_mesh_id("l");
    o->set_name(absl::StrCat("o", i));
    o->mutable_transform()->mutable_translation()->set_x(3 * i);
    o->set_hidden(i % 7 == 3);
  }
  return proto;
}

v1::Object* Named(v1::Scene& proto, int i) {
  for (v1::Object& o : *proto.mutable_objects())
    if (o.name() == absl::StrCat("o", i)) return &o;
  return nullptr;
}

// An update that shows, hides and moves objects all over the scene lays the polygon array out
// again in one pass: the result is a fresh build of the changed scene, polygon for polygon.
TEST(SceneUpdate, ManyShownHiddenAndMovedObjectsEqualAFreshBuild) {
  constexpr int kObjects = 600;
  v1::Scene proto = ManyNamedObjects(kObjects);
  Scene live = Build(proto);
  ASSERT_EQ(live.objects.size(), static_cast<size_t>(kObjects));
  v1::SceneUpdate update;
  for (int i = kObjects - 1; i >= 0; i -= 2) {  // out of scene order, every other object
    v1::ObjectUpdate* o = update.add_objects();
    o->set_name(absl::StrCat("o", i));
    v1::Object& loaded = *Named(proto, i);
    if (i % 5 == 0) {
      o->set_visibility(loaded.hidden() ? v1::VISIBILITY_SHOWN : v1::VISIBILITY_HIDDEN);
      loaded.set_hidden(!loaded.hidden());
    }
    if (i % 4 == 1) {
      *o->mutable_transform() = Moved();
      *loaded.mutable_transform() = Moved();
    }
  }
  // One object named many times: the last transform and visibility win.
  for (int k = 0; k < 50; ++k) {
    v1::ObjectUpdate* o = update.add_objects();
    o->set_name("o2");
    o->mutable_transform()->mutable_translation()->set_z(-k);
    o->set_visibility(k % 2 == 0 ? v1::VISIBILITY_HIDDEN : v1::VISIBILITY_SHOWN);
  }
  Named(proto, 2)->mutable_transform()->mutable_translation()->set_z(-49);
  Named(proto, 2)->mutable_transform()->mutable_translation()->set_x(0);
  Named(proto, 2)->set_hidden(false);
  ASSERT_TRUE(ApplySceneUpdate(update, &live).ok());
  ExpectSameScene(live, Build(proto));
}

// The scene's name index finds every named object, and a copy of the scene keeps it.
TEST(SceneUpdate, TheNameIndexFindsEveryObjectOfACopy) {
  const Scene built = Build(ManyNamedObjects(100));
  const Scene copy = built;
  ASSERT_EQ(copy.object_index.size(), copy.objects.size());
  for (size_t i = 0; i < copy.objects.size(); ++i)
    EXPECT_EQ(copy.object_index.at(copy.objects[i].name), i);
}

// A stop test that says stop ends the check or the update, CANCELLED naming how far it got, and
// leaves the scene as it was.
TEST(SceneUpdate, AStoppedUpdateChangesNothing) {
  constexpr int kObjects = 3000;
  Scene live = Build(ManyNamedObjects(kObjects));
  const Scene original = live;
  v1::SceneUpdate update;
  for (int repeat = 0; repeat < 4; ++repeat)
    for (int i = 0; i < kObjects; ++i) {
      v1::ObjectUpdate* o = update.add_objects();
      o->set_name(absl::StrCat("o", i));
      *o->mutable_transform() = Moved();
    }
  int asked = 0;
  const std::function<bool()> stop = [&] { return ++asked > 1; };
  const absl::Status check = CheckSceneUpdate(live, update, stop);
  EXPECT_TRUE(absl::IsCancelled(check)) << check;
  EXPECT_NE(check.message().find("stopped (deadline or cancellation) while it was checked at "
                                 "update.objects[8191] of 12000"),
            std::string::npos)
      << check;
  for (int allowed : {1, 3, 4}) {  // stopped while checking, gathering, placing
    asked = 0;
    const std::function<bool()> later = [&] { return ++asked > allowed; };
    const absl::Status apply = ApplySceneUpdate(update, &live, later);
    EXPECT_TRUE(absl::IsCancelled(apply)) << apply;
    ExpectSameScene(live, original);
  }
  EXPECT_TRUE(ApplySceneUpdate(update, &live, [] { return false; }).ok());
}

TEST(SceneUpdate, ALongNameIsCutInTheError) {
  Scene live = Build(MakeDemoScene());
  v1::SceneUpdate update;
  update.add_objects()->set_name(std::string(100000, 'x'));
  const absl::Status status = CheckSceneUpdate(live, update);
  EXPECT_TRUE(absl::IsInvalidArgument(status));
  EXPECT_LT(status.message().size(), 300u);
  EXPECT_NE(status.message().find("100000 characters"), std::string::npos) << status;
}

// Merging costs in proportion to what is merged: 2,000 merges of a one-object update into an
// update of 20,000 objects stay one entry per object and finish at once.
TEST(SceneUpdate, MergingIntoABigUpdateCostsTheSmallOne) {
  MergedSceneUpdate merged;
  v1::SceneUpdate big;
  for (int i = 0; i < 20000; ++i) big.add_objects()->set_name(absl::StrCat("o", i));
  merged.Merge(big);
  v1::SceneUpdate small;
  small.add_objects()->set_name("o7");
  const auto start = std::chrono::steady_clock::now();
  for (int k = 0; k < 2000; ++k) {
    small.mutable_objects(0)->mutable_transform()->mutable_translation()->set_x(k);
    merged.Merge(small);
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_LT(seconds, 0.5);  // tens of microseconds in all; a rebuild per merge takes seconds
  EXPECT_FALSE(merged.empty());
  const v1::SceneUpdate taken = merged.Take();
  EXPECT_TRUE(merged.empty());
  ASSERT_EQ(taken.objects_size(), 20000);
  EXPECT_EQ(taken.objects(7).transform().translation().x(), 1999);
}

}  // namespace
}  // namespace aperture
