// A town at night for the built-in night scene (scene/night_scene.h): a grid of streets lit by
// rows of street lights, blocks of buildings whose walls carry a texture of windows, some of them
// lit, and a lit motorway. Deterministic: the same district is the same town in every process.
#pragma once

#include "aperture/v1/scene.pb.h"

namespace aperture {

// The light group of the town's street lights.
inline constexpr char kStreetLightGroup[] = "street-lights";

// A rectangle of the town, x0 < x1, z0 < z1, metres, on the ground (y = 0).
struct TownDistrict {
  const char* name;  // prefixes its meshes' ids
  double x0, z0, x1, z1;
  // Where its buildings are tallest (a centre of town), and how far that reaches.
  double centre_x, centre_z, centre_radius_m;
  unsigned seed;
};

// The town's materials and textures ("facade", "roof", "town-ground"), once per scene.
void AddTownMaterials(v1::Scene* scene);

// A motorway running east-west (along x) from x0 to x1 at z, lit from masts on its central
// reservation.
struct Motorway {
  const char* name;  // prefixes its mesh's id
  double x0, x1, z, width_m;
};

void AddMotorway(const Motorway& road, v1::Scene* scene);

// A district's ground, buildings (meshes "<name>-buildings", placed by one object each) and
// street lights (rows of kStreetLightGroup).
void AddTownDistrict(const TownDistrict& district, v1::Scene* scene);

}  // namespace aperture
