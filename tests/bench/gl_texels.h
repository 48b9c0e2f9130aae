// A scene texture as the RGBA8 texels a GL peer uploads (night_load_bench.cc's llvmpipe frame):
// a raster texture's pyramid base, or a packed vector texture (seed 001) decoded and box-averaged
// to at most a given side, since GL has no packed vector textures. Colours stay linear, as the
// engine takes them; premultiplied ones are divided by their alpha again, as GL's alpha test and
// blending expect.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "base/image.h"
#include "scene/scene.h"

namespace aperture {

struct GlTexels {
  int width = 0, height = 0;
  std::vector<uint8_t> rgba;  // row 0 first: at t = 0, where the engine's v = 0 is
  std::string source;         // what the texels were made from, for the benchmark's notes
};

// Unimplemented for a texture of neither kind (the caller then draws its average colour).
absl::StatusOr<GlTexels> GlTexelsOf(const SceneTexture& texture, int max_side);

// The mean colour of a texture over one period, from its nearest samples on a grid.
Rgba MeanColour(const SceneTexture& texture);

}  // namespace aperture
