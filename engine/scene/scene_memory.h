// What a scene will hold in memory once built, estimated from its request before anything is
// decoded or built: the server admits a LoadScene against its budget with this
// figure, so a 196 KB PNG that declares 8192 x 8192 texels is weighed as the 1.4 GB it becomes.
#pragma once

#include <cstdint>
#include <string>

#include "absl/status/statusor.h"
#include "aperture/v1/scene.pb.h"

namespace aperture {

struct SceneMemory {
  uint64_t texture_bytes = 0;   // float RGBA mip-maps and packed textures
  uint64_t table_bytes = 0;     // seed 000 tables of the textures that materials filter aniso
  uint64_t geometry_bytes = 0;  // polygons after triangulation (an upper bound)
  uint64_t total() const { return texture_bytes + table_bytes + geometry_bytes; }
  std::string ToString() const;  // "1432.1 MiB (textures 1365.3, aniso tables 0, geometry 66.8)"
};

// Texture sources: encoded bytes (their header), checkerboards (their size); a file source is
// read for its header only when `read_files` (the server never reads client paths). Errors are
// those the build would give for a source that is no texture.
absl::StatusOr<SceneMemory> EstimateSceneMemory(const v1::Scene& scene, bool read_files = false);

}  // namespace aperture
