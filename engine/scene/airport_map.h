// The built-in airport's ground map: Amsterdam Schiphol's aeroway features from OpenStreetMap
// (© OpenStreetMap contributors, ODbL 1.0; ../shared/data/vector/osm_eham_schiphol_8192.png,
// 9.16 km square, 1.12 m a texel) packed as a seed 001 vector texture by `aperture-tex pack`
// (engine/scene/data/eham_schiphol_8192.apv, 105 KB, .apv version 2), embedded in the binary so
// that every tool and the server has it without data files.
#pragma once

#include <cstdint>
#include <span>

#include "scene/vec.h"

namespace aperture {

// The .apv file's bytes.
std::span<const uint8_t> AirportMapApv();

// What the map shows, in its texel units (8192 a side): the south end of runway 18R/36L (the
// Polderbaan) and its direction towards the north end, measured on the map.
inline constexpr double kAirportMapMetres = 9160;  // one side of the map
inline constexpr double kPolderbaanSouthX = 1089.5, kPolderbaanSouthY = 3990;
inline constexpr double kPolderbaanNorthX = 1278.8, kPolderbaanNorthY = 594;
// The parallel runway 36C (3,300 m x 45 m, the Zwanenburgbaan): its south end's and north end's
// centres.
inline constexpr double k36CSouthX = 2828, k36CSouthY = 6655, k36CNorthX = 2987, k36CNorthY = 3708;

// Where the built-in airport puts the map's texel (x, y) (column, row from the top) on the ground
// (y = 0): the Polderbaan's south end at (0, 0, 200), the runway running along -z, +x east of it
// (scene/airport_scene.cc's texture transform). Features read off the map (taxiways, another
// runway) are placed with it.
Vec3 AirportMapToWorld(double texel_x, double texel_y);

}  // namespace aperture
