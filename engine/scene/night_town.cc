#include "scene/night_town.h"

#include <cmath>
#include <cstdint>
#include <string>

#include "scene/demo_geometry.h"
#include "scene/vec.h"
#include "texture/procedural.h"

namespace aperture {
namespace {

using demo::AddEncodedTexture;
using demo::AddMaterial;
using demo::AddPolygon;

// Street centre lines every kBlockX m along x and kBlockZ m along z; buildings stand kSetbackM
// from a street's centre line, the lights kKerbM from it, kLampM up, every kLampSpacingM.
constexpr double kBlockX = 60, kBlockZ = 48;
constexpr double kSetbackM = 8, kKerbM = 5, kLampM = 10, kLampSpacingM = 22;
// Every kAvenueEvery-th street is an avenue under white LED lamps; the others have sodium lamps.
constexpr int kAvenueEvery = 4;
// Facade texture: kCells x kCells windows of kFloorM, one repeat kCells x kFloorM metres square.
constexpr int kCellTexels = 16, kCells = 16;
constexpr double kFloorM = 3;

// A deterministic hash of a few integers to [0, 1).
double Hash01(uint32_t a, uint32_t b, uint32_t c, uint32_t d) {
  uint64_t h = 0x9E3779B97F4A7C15ull;
  for (uint32_t v : {a, b, c, d}) {
    h ^= v + 0x9E3779B97F4A7C15ull + (h << 6) + (h >> 2);
    h ^= h >> 31;
    h *= 0xBF58476D1CE4E5B9ull;
    h ^= h >> 27;
  }
  return static_cast<double>(h >> 11) * (1.0 / 9007199254740992.0);
}

// Walls of dark concrete with a window in each cell: a quarter of them lit, warm (lamps) or
// cool (screens); the rest dark glass. Drawn unlit, so the lit windows glow at night.
Image MakeFacadeTexture() {
  const int size = kCellTexels * kCells;
  Image image(size, size, {0.022f, 0.021f, 0.020f, 1});
  for (int cy = 0; cy < kCells; ++cy) {
    for (int cx = 0; cx < kCells; ++cx) {
      const double lit = Hash01(cx, cy, 1, 7), shade = Hash01(cx, cy, 2, 7);
      Rgba window{0.010f, 0.012f, 0.018f, 1};
      if (lit < 0.22) {
        const float k = static_cast<float>(0.35 + 0.55 * shade);
        window = {1.0f * k, 0.78f * k, 0.45f * k, 1};
      } else if (lit < 0.27) {
        const float k = static_cast<float>(0.25 + 0.3 * shade);
        window = {0.55f * k, 0.70f * k, 1.0f * k, 1};
      }
      for (int y = 5; y < 12; ++y)
        for (int x = 3; x < 13; ++x) image.at(cx * kCellTexels + x, cy * kCellTexels + y) = window;
    }
  }
  return image;
}

// A building [x0, x1] x [z0, z1], `height` tall: four walls and a flat roof, each seen from
// outside counter-clockwise.
void AddBuilding(v1::Mesh* mesh, double x0, double z0, double x1, double z1, double height) {
  const double y = height;
  AddPolygon(mesh, {{x0, 0, z1}, {x1, 0, z1}, {x1, y, z1}, {x0, y, z1}});  // +z
  AddPolygon(mesh, {{x1, 0, z0}, {x0, 0, z0}, {x0, y, z0}, {x1, y, z0}});  // -z
  AddPolygon(mesh, {{x1, 0, z1}, {x1, 0, z0}, {x1, y, z0}, {x1, y, z1}});  // +x
  AddPolygon(mesh, {{x0, 0, z0}, {x0, 0, z1}, {x0, y, z1}, {x0, y, z0}});  // -x
  AddPolygon(mesh, {{x0, y, z1}, {x1, y, z1}, {x1, y, z0}, {x0, y, z0}})->set_material_id("roof");
}

// The buildings of the block whose south-west street corner is (x, z): near the district's
// centre two by two lots, tall; elsewhere two lots side by side, low; some left empty (a square,
// a car park).
void AddBlock(const TownDistrict& d, int i, int j, double x, double z, v1::Mesh* mesh) {
  const double inner_x0 = x + kSetbackM, inner_x1 = x + kBlockX - kSetbackM;
  const double inner_z0 = z + kSetbackM, inner_z1 = z + kBlockZ - kSetbackM;
  if (Hash01(i, j, d.seed, 1) < 0.06) return;  // a square
  const double from_centre = std::hypot(x + kBlockX / 2 - d.centre_x, z + kBlockZ / 2 - d.centre_z);
  const double central = std::max(0.0, 1 - from_centre / d.centre_radius_m);
  const int lots_z = central > 0 ? 2 : 1;
  constexpr double kGap = 4;
  const double lot_x = (inner_x1 - inner_x0 - kGap) / 2;
  const double lot_z = (inner_z1 - inner_z0 - kGap * (lots_z - 1)) / lots_z;
  for (int lot = 0; lot < 2 * lots_z; ++lot) {
    const double r = Hash01(i, j, d.seed, 10 + lot), s = Hash01(i, j, d.seed, 20 + lot);
    if (r < 0.05) continue;  // an empty lot
    const int column = lot % 2, row = lot / 2;
    const double lx0 = inner_x0 + column * (lot_x + kGap), lz0 = inner_z0 + row * (lot_z + kGap);
    // Set back from the lot's inner sides by up to a third of it.
    const double w = lot_x * (0.65 + 0.35 * s), depth = lot_z * (0.65 + 0.35 * r);
    const double bx0 = column ? lx0 + lot_x - w : lx0;
    const double bz0 = lots_z > 1 && row ? lz0 + lot_z - depth : lz0;
    const int floors = central > 0 ? 4 + static_cast<int>(central * 14 * (0.4 + 0.6 * r))
                                   : 1 + static_cast<int>(2.2 * s);
    AddBuilding(mesh, bx0, bz0, bx0 + w, bz0 + depth, floors * kFloorM);
  }
}

void SetVec(v1::Vec3* out, const Vec3& v) {
  out->set_x(v.x);
  out->set_y(v.y);
  out->set_z(v.z);
}

// A row of street lamps from `a` to `b`, `spacing` apart: sodium lamps seen from above at 300 cd,
// LED avenue lamps at 400 cd (realistic orders of magnitude for semi-cut-off luminaires seen from
// the air).
void AddLamps(const Vec3& a, const Vec3& b, bool avenue, v1::Scene* scene,
              double spacing = kLampSpacingM) {
  const int count = static_cast<int>(std::floor(Length(b - a) / spacing)) + 1;
  v1::LightRow* row = scene->add_light_rows();
  SetVec(row->mutable_start(), a);
  SetVec(row->mutable_end(), a + Normalize(b - a) * (spacing * (count - 1)));
  row->set_count(static_cast<uint32_t>(count));
  v1::LightPoint* lamp = row->mutable_light();
  // Linear colours scaled to luminance 1 (intensity_cd is photometric).
  const double r = avenue ? 0.95 : 1.0, g = avenue ? 0.97 : 0.55, bl = avenue ? 1.0 : 0.16;
  const double luminance = 0.2126 * r + 0.7152 * g + 0.0722 * bl;
  lamp->mutable_color()->set_r(static_cast<float>(r / luminance));
  lamp->mutable_color()->set_g(static_cast<float>(g / luminance));
  lamp->mutable_color()->set_b(static_cast<float>(bl / luminance));
  lamp->set_intensity_cd(avenue ? 400 : 300);
  lamp->set_group(kStreetLightGroup);
  lamp->set_radius_m(0.3);
}

}  // namespace

void AddTownMaterials(v1::Scene* scene) {
  AddEncodedTexture(*scene, "facade", MakeFacadeTexture());
  AddEncodedTexture(*scene, "roof",
                    MakeNoiseTexture(64, 31, {0.10f, 0.10f, 0.11f, 1}, {0.22f, 0.21f, 0.20f, 1}));
  AddEncodedTexture(*scene, "town-ground",
                    MakeNoiseTexture(128, 37, {0.08f, 0.08f, 0.09f, 1}, {0.20f, 0.20f, 0.21f, 1}));
  v1::Material* facade = AddMaterial(*scene, "facade", 1, 1, 1, "facade", kCells * kFloorM);
  facade->set_unlit(true);
  facade->set_single_sided(true);
  facade->set_filter(v1::TEXTURE_FILTER_TRILINEAR);
  v1::Material* roof = AddMaterial(*scene, "roof", 1, 1, 1, "roof", 20);
  roof->set_single_sided(true);
  roof->set_filter(v1::TEXTURE_FILTER_TRILINEAR);
  v1::Material* ground = AddMaterial(*scene, "town-ground", 1, 1, 1, "town-ground", 40);
  ground->set_filter(v1::TEXTURE_FILTER_TRILINEAR);
}

void AddTownDistrict(const TownDistrict& d, v1::Scene* scene) {
  const std::string name = d.name;
  v1::Mesh* ground = scene->add_meshes();
  ground->set_id(name + "-ground");
  ground->set_material_id("town-ground");
  demo::AddFlatRect(ground, d.x0, d.z0, d.x1, d.z1, 0.01);

  v1::Mesh* buildings = scene->add_meshes();
  buildings->set_id(name + "-buildings");
  buildings->set_material_id("facade");
  const int columns = static_cast<int>(std::floor((d.x1 - d.x0) / kBlockX));
  const int rows = static_cast<int>(std::floor((d.z1 - d.z0) / kBlockZ));
  for (int i = 0; i < columns; ++i)
    for (int j = 0; j < rows; ++j)
      AddBlock(d, i, j, d.x0 + i * kBlockX, d.z0 + j * kBlockZ, buildings);

  // Street lights on both kerbs, staggered: north-south streets at every x0 + i kBlockX,
  // east-west ones at every z0 + j kBlockZ.
  for (int i = 0; i <= columns; ++i) {
    const double x = d.x0 + i * kBlockX;
    const bool avenue = i % kAvenueEvery == 0;
    AddLamps({x - kKerbM, kLampM, d.z0}, {x - kKerbM, kLampM, d.z1}, avenue, scene);
    AddLamps({x + kKerbM, kLampM, d.z0 + kLampSpacingM / 2}, {x + kKerbM, kLampM, d.z1}, avenue,
             scene);
  }
  for (int j = 0; j <= rows; ++j) {
    const double z = d.z0 + j * kBlockZ;
    const bool avenue = j % kAvenueEvery == 0;
    AddLamps({d.x0, kLampM, z - kKerbM}, {d.x1, kLampM, z - kKerbM}, avenue, scene);
    AddLamps({d.x0 + kLampSpacingM / 2, kLampM, z + kKerbM}, {d.x1, kLampM, z + kKerbM}, avenue,
             scene);
  }
  for (v1::Mesh* mesh : {ground, buildings}) scene->add_objects()->set_mesh_id(mesh->id());
}

void AddMotorway(const Motorway& road, v1::Scene* scene) {
  v1::Mesh* surface = scene->add_meshes();
  surface->set_id(std::string(road.name) + "-surface");
  surface->set_material_id("town-ground");
  demo::AddFlatRect(surface, road.x0, road.z - road.width_m / 2, road.x1, road.z + road.width_m / 2,
                    0.015);
  scene->add_objects()->set_mesh_id(surface->id());
  // Masts on the central reservation, 12 m up, 40 m apart, an arm over each carriageway.
  constexpr double kMastM = 12, kMastSpacingM = 40, kArmM = 3;
  for (double arm : {-kArmM, kArmM})
    AddLamps({road.x0, kMastM, road.z + arm}, {road.x1, kMastM, road.z + arm}, false, scene,
             kMastSpacingM);
}

}  // namespace aperture
