#include "scene/demo_scene.h"

#include <cmath>

#include "scene/demo_geometry.h"
#include "texture/procedural.h"

namespace aperture {
namespace {

using namespace demo;  // NOLINT: the shared airfield geometry

v1::Scene BuildDemoScene() {
  v1::Scene scene;
  scene.set_name("demo-airfield");
  SetDemoWeather(scene);

  AddEncodedTexture(scene, "grass",
                    MakeNoiseTexture(512, 11, {0.10f, 0.20f, 0.05f, 1}, {0.35f, 0.50f, 0.18f, 1}));
  AddEncodedTexture(scene, "asphalt",
                    MakeNoiseTexture(512, 23, {0.12f, 0.12f, 0.13f, 1}, {0.32f, 0.32f, 0.33f, 1}));
  v1::Texture* checker = scene.add_textures();
  checker->set_id("checker");
  checker->mutable_checkerboard()->set_size(1024);
  checker->mutable_checkerboard()->set_cells(8);

  AddMaterial(scene, "grass", 1, 1, 1, "grass", 8);
  AddMaterial(scene, "asphalt", 1, 1, 1, "asphalt", 20);
  AddMaterial(scene, "checker", 0.9f, 0.9f, 0.9f, "checker", 200);
  AddMaterial(scene, "paint", 0.85f, 0.85f, 0.82f);
  AddMaterial(scene, "hangar", 0.55f, 0.57f, 0.60f);
  AddMaterial(scene, "tank", 0.80f, 0.80f, 0.76f);
  AddMaterial(scene, "livery", 0.90f, 0.90f, 0.92f);

  v1::Mesh* ground = scene.add_meshes();
  ground->set_id("ground");
  ground->set_material_id("grass");
  AddFlatRect(ground, -10000, -10000, 10000, 10000, 0);

  // Runway 3000 m x 45 m along -z, its threshold at z = 200; a parallel taxiway.
  v1::Mesh* runway = scene.add_meshes();
  runway->set_id("runway");
  runway->set_material_id("asphalt");
  AddFlatRect(runway, -22.5, -2800, 22.5, 200, 0.05);
  AddFlatRect(runway, -172.5, -2700, -149.5, 100, 0.05);
  for (double z : {100.0, -1300.0, -2600.0})
    AddFlatRect(runway, -149.5, z - 11.5, -22.5, z + 11.5, 0.05);

  v1::Mesh* marks = scene.add_meshes();
  marks->set_id("markings");
  marks->set_material_id("paint");
  for (int i = 0; i < 8; ++i) {  // threshold bars, both sides of the centreline
    const double x = 3.0 + i * 2.3;
    AddFlatRect(marks, x, 150, x + 1.8, 190, 0.1);
    AddFlatRect(marks, -x - 1.8, 150, -x, 190, 0.1);
  }
  for (double z = 100; z > -2700; z -= 50) AddFlatRect(marks, -0.45, z - 30, 0.45, z, 0.1);
  for (double z : {-100.0, -250.0, -400.0}) {  // touchdown zone pairs
    AddFlatRect(marks, 6, z - 22.5, 10, z, 0.1);
    AddFlatRect(marks, -10, z - 22.5, -6, z, 0.1);
  }
  for (double x : {-22.0, 21.1}) AddFlatRect(marks, x, -2800, x + 0.9, 200, 0.1);  // edge lines

  v1::Mesh* test_area = scene.add_meshes();
  test_area->set_id("checker-area");
  test_area->set_material_id("checker");
  AddFlatRect(test_area, 50, -150, 250, 50, 0.05);

  v1::Mesh* hangars = scene.add_meshes();
  hangars->set_id("hangars");
  hangars->set_material_id("hangar");
  for (int i = 0; i < 4; ++i) AddBox(hangars, -190, -60.0 - i * 90, -130, 0.0 - i * 90, 18);

  v1::Mesh* tanks = scene.add_meshes();
  tanks->set_id("tanks");
  tanks->set_material_id("tank");
  for (int i = 0; i < 3; ++i) AddTank(tanks, 160 + i * 35.0, -420, 12, 14, 32);

  // A town beyond the airfield: a 16 x 16 grid of buildings of varied height.
  v1::Mesh* town = scene.add_meshes();
  town->set_id("town");
  town->set_material_id("hangar");
  for (int i = 0; i < 16; ++i) {
    for (int j = 0; j < 16; ++j) {
      const double x = -900 + i * 28.0, z = -1700 + j * 28.0;
      const double height = 8 + ((i * 7 + j * 13) % 11) * 3.0;
      AddBox(town, x, z, x + 18, z + 18, height);
    }
  }

  AddAircraftAndObjects(scene);
  return scene;
}

}  // namespace

// Generating and encoding the textures takes a while: once per process.
v1::Scene MakeDemoScene() {
  static const v1::Scene* const demo = new v1::Scene(BuildDemoScene());
  return *demo;
}

v1::Transform DemoAircraftAt(double seconds) {
  // Lined up on the runway's centreline 150 m past the threshold (z = 200), 370 m ahead of the
  // camera, then rolling for take-off at 2 m/s^2. The wheels stand just above the paint (y = 0.1):
  // gear legs through the runway's layers would make cells of interpenetrating pieces.
  v1::Transform t;
  t.mutable_translation()->set_y(0.15);
  t.mutable_translation()->set_z(50 - seconds * seconds);
  return t;
}

Camera DemoCamera() {
  Camera camera;
  camera.position = {0, 14, 420};
  camera.pitch_deg = -5;
  camera.vertical_fov_deg = 60;
  camera.near = 0.5;
  return camera;
}

}  // namespace aperture
