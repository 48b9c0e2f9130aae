#include "scene/airport_map.h"

#include <cmath>

// The file is assembled into read-only data (`.incbin`): no generated source, no copy at start.
#ifndef APERTURE_AIRPORT_MAP_FILE
#error "APERTURE_AIRPORT_MAP_FILE must name the .apv file (engine/CMakeLists.txt)"
#endif

asm(".section .rodata.aperture_airport_map, \"a\", @progbits\n"
    ".balign 64\n"
    ".globl aperture_airport_map_begin\n"
    "aperture_airport_map_begin:\n"
    ".incbin \"" APERTURE_AIRPORT_MAP_FILE
    "\"\n"
    ".globl aperture_airport_map_end\n"
    "aperture_airport_map_end:\n"
    ".previous\n");

extern "C" const uint8_t aperture_airport_map_begin[];
extern "C" const uint8_t aperture_airport_map_end[];

namespace aperture {

std::span<const uint8_t> AirportMapApv() {
  return {aperture_airport_map_begin, aperture_airport_map_end};
}

Vec3 AirportMapToWorld(double texel_x, double texel_y) {
  // The runway's direction on the map, (s, -c): going -z in the world; (c, s): going +x.
  const double dx = kPolderbaanNorthX - kPolderbaanSouthX,
               dy = kPolderbaanNorthY - kPolderbaanSouthY;
  const double length = std::hypot(dx, dy), s = dx / length, c = -dy / length;
  constexpr double kMetresPerTexel = kAirportMapMetres / 8192;
  const double u = texel_x - kPolderbaanSouthX, v = texel_y - kPolderbaanSouthY;
  return {kMetresPerTexel * (u * c + v * s), 0, 200 - kMetresPerTexel * (u * s - v * c)};
}

}  // namespace aperture
