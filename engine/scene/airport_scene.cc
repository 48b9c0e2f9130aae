#include "scene/airport_scene.h"

#include <cmath>
#include <string>

#include "scene/airport_map.h"
#include "scene/airport_runways.h"
#include "scene/approach_camera.h"
#include "scene/demo_geometry.h"
#include "scene/demo_scene.h"
#include "scene/runway_markings.h"
#include "texture/procedural.h"

namespace aperture {
namespace {

using namespace demo;  // NOLINT: the shared airfield geometry

constexpr double kMapTexels = 8192;

// The map's texture transform (seed 003's F2 on the ground's x-z projection): one repeat is the
// map's side, turned so that the runway runs along -z from its south end at (0, 0, 200), where
// the demo's threshold is.
v1::TextureTransform MapTransform(double* sin_r, double* cos_r) {
  const double dx = kPolderbaanNorthX - kPolderbaanSouthX,
               dy = kPolderbaanNorthY - kPolderbaanSouthY;
  const double length = std::hypot(dx, dy);
  // Going -z in the world moves (sin r, -cos r) / R in (u, v): that is the runway's direction.
  const double s = dx / length, c = -dy / length;
  v1::TextureTransform t;
  t.set_repeat_u(kAirportMapMetres);
  t.set_rotation_deg(std::atan2(s, c) * 180 / kPi);
  // u = (c x - s z) / R + u0, v = (s x + c z) / R + v0 puts the south end at x = 0, z = 200.
  t.set_offset_u(kPolderbaanSouthX / kMapTexels + s * 200 / kAirportMapMetres);
  t.set_offset_v(kPolderbaanSouthY / kMapTexels - c * 200 / kAirportMapMetres);
  *sin_r = s, *cos_r = c;
  return t;
}

// The map's one period as a ground polygon: the world points of its (u, v) corners.
void AddMapGround(v1::Mesh* mesh, const v1::TextureTransform& t, double s, double c) {
  const double r = kAirportMapMetres;
  v1::Polygon* p = mesh->add_polygons();
  for (const auto& [u, v] : {std::pair{0.0, 1.0}, {1.0, 1.0}, {1.0, 0.0}, {0.0, 0.0}}) {
    const double a = (u - t.offset_u()) * r, b = (v - t.offset_v()) * r;
    v1::Vec3* q = p->add_vertices();
    q->set_x(c * a + s * b);
    q->set_y(0);
    q->set_z(-s * a + c * b);
  }
}

// A cut-out tree: a crown of leaves over a trunk, alpha 1 on them and 0 around (the colour there
// black, as exported cut-outs often are). 64 x 128 texels, row 0 at the top.
Image MakeTreeTexture() {
  const Image leaves = MakeNoiseTexture(64, 5, {0.05f, 0.16f, 0.04f, 1}, {0.22f, 0.42f, 0.12f, 1});
  const Image ragged = MakeNoiseTexture(64, 9, {0, 0, 0, 1}, {1, 1, 1, 1});
  Image tree(64, 128, {0, 0, 0, 0});
  for (int y = 0; y < 128; ++y)
    for (int x = 0; x < 64; ++x) {
      const double dx = (x + 0.5 - 32) / 30, dy = (y + 0.5 - 50) / 46;
      const double edge = 0.8 + 0.35 * ragged.at(x, y % 64).r;  // a ragged outline
      if (dx * dx + dy * dy < edge * edge) {
        tree.at(x, y) = leaves.at(x, y % 64);
      } else if (x >= 29 && x < 35 && y >= 80) {
        tree.at(x, y) = {0.20f, 0.14f, 0.09f, 1};
      }
    }
  return tree;
}

// Two crossed vertical quads carrying the tree texture, standing at (x, 0, z).
void AddTree(v1::Mesh* mesh, double x, double z, double height) {
  const double w = height / 4;
  const double ends[2][4] = {{x - w, z, x + w, z}, {x, z + w, x, z - w}};
  for (const auto& e : ends) {
    v1::Polygon* p = AddPolygon(
        mesh, {{e[0], 0, e[1]}, {e[2], 0, e[3]}, {e[2], height, e[3]}, {e[0], height, e[1]}});
    for (const auto& [u, v] : {std::pair{0.0, 1.0}, {1.0, 1.0}, {1.0, 0.0}, {0.0, 0.0}}) {
      v1::Vec2* uv = p->add_uvs();
      uv->set_u(u);
      uv->set_v(v);
    }
  }
}

v1::Scene BuildAirportScene() {
  v1::Scene scene;
  scene.set_name("airport-schiphol");
  SetDemoWeather(scene);
  // Schiphol's place (the aerodrome reference point, 52.31 N 4.76 E), so that a frame's time of
  // day (aperture-render --time) lights it; the map's north is up, so the world's -z, along the
  // Polderbaan, points at the runway's true bearing.
  v1::TimeOfDay* time_of_day = scene.mutable_time_of_day();
  time_of_day->mutable_place()->set_latitude_deg(52.31);
  time_of_day->mutable_place()->set_longitude_deg(4.76);
  time_of_day->set_grid_north_deg(
      std::atan2(kPolderbaanNorthX - kPolderbaanSouthX, kPolderbaanSouthY - kPolderbaanNorthY) *
      180 / kPi);

  v1::Texture* map = scene.add_textures();
  map->set_id("schiphol");
  const std::span<const uint8_t> apv = AirportMapApv();
  map->set_encoded(std::string(apv.begin(), apv.end()));
  AddEncodedTexture(scene, "tree", MakeTreeTexture());

  double s = 0, c = 1;
  v1::Material* ground = AddMaterial(scene, "map", 1, 1, 1, "schiphol", 1);
  *ground->mutable_texture_transform() = MapTransform(&s, &c);
  // Beyond the map: its grass colour (8-bit values taken as linear, as the map's are).
  AddMaterial(scene, "grass", 141 / 255.0f, 179 / 255.0f, 96 / 255.0f);
  AddMaterial(scene, "hangar", 0.55f, 0.57f, 0.60f);
  AddMaterial(scene, "concrete", 0.70f, 0.69f, 0.66f);
  v1::Material* glass = AddMaterial(scene, "glass", 0.30f, 0.45f, 0.55f);
  glass->set_alpha_mode(v1::ALPHA_MODE_BLEND);
  glass->set_transparency(0.55f);
  v1::Material* tree = AddMaterial(scene, "tree", 1, 1, 1, "tree", 1);
  tree->set_alpha_mode(v1::ALPHA_MODE_MASK);
  tree->set_filter(v1::TEXTURE_FILTER_TRILINEAR);
  AddMaterial(scene, "livery", 0.90f, 0.90f, 0.92f);

  v1::Mesh* grass = scene.add_meshes();
  grass->set_id("grass");
  grass->set_material_id("grass");
  AddFlatRect(grass, -12000, -12000, 12000, 12000, -0.05);  // under the map
  v1::Mesh* map_ground = scene.add_meshes();
  map_ground->set_id("map");
  map_ground->set_material_id("map");
  AddMapGround(map_ground, scene.materials(0).texture_transform(), s, c);

  // The runways' Annex 14 markings over the map's runways (scene/runway_markings.h).
  for (const RunwayDescription& runway : {Polderbaan36L(), Zwanenburgbaan36C()})
    if (!AddRunwayMarkings(runway, &scene).ok()) return {};  // known-good data: the tests catch it

  // West of the runway, on the map's grass: four hangars and the control tower, whose glass cab
  // shows the sky and the ground through it.
  v1::Mesh* hangars = scene.add_meshes();
  hangars->set_id("hangars");
  hangars->set_material_id("hangar");
  for (int i = 0; i < 4; ++i) AddBox(hangars, -290, -160.0 - i * 90, -230, -100.0 - i * 90, 18);
  v1::Mesh* tower = scene.add_meshes();
  tower->set_id("tower");
  tower->set_material_id("concrete");
  AddSolidBox(tower, {-213, 0, -623}, {-207, 34, -617}, kTop | kBottom);
  AddSolidBox(tower, {-216, 40, -626}, {-204, 41, -614});  // the cab's roof
  v1::Mesh* cab = scene.add_meshes();
  cab->set_id("tower-cab");
  cab->set_material_id("glass");
  AddSolidBox(cab, {-216, 34, -626}, {-204, 40, -614}, kTop);

  // Rows of cut-out trees along the west side and a copse east of the runway.
  v1::Mesh* trees = scene.add_meshes();
  trees->set_id("trees");
  trees->set_material_id("tree");
  for (int i = 0; i < 60; ++i) {
    const double z = 150 - i * 30.0, height = 9 + (i * 7 % 5);
    AddTree(trees, -120, z, height);
    AddTree(trees, -138, z - 15, height + 2);
  }
  for (int i = 0; i < 5; ++i)
    for (int j = 0; j < 4; ++j) AddTree(trees, 140 + i * 14.0, -300 - j * 17.0, 10 + (i + j) % 4);

  AddAircraftAndObjects(scene);
  return scene;
}

}  // namespace

Camera AirportCamera() {
  return ApproachCamera(Polderbaan36L(), kAirportCameraDistanceM, kAirportCameraPitchDeg,
                        kAirportCameraFovDeg);
}

v1::Scene MakeAirportScene() {
  static const v1::Scene* const airport = new v1::Scene(BuildAirportScene());
  return *airport;
}

}  // namespace aperture
