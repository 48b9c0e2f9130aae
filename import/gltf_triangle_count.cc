#include "gltf_triangle_count.h"

#include <limits>
#include <optional>
#include <vector>

#include "absl/strings/str_cat.h"
#include "gltf_accessor.h"

namespace aperture {
namespace {

absl::Status Invalid(const std::string& where, const std::string& what) {
  return absl::InvalidArgumentError(absl::StrCat(where, ": ", what));
}

uint64_t SaturatingAdd(uint64_t a, uint64_t b) {
  return b > std::numeric_limits<uint64_t>::max() - a ? std::numeric_limits<uint64_t>::max()
                                                      : a + b;
}

absl::StatusOr<uint64_t> MeshTriangles(const tinygltf::Model& model, int index) {
  uint64_t triangles = 0;
  const tinygltf::Mesh& mesh = model.meshes[index];
  for (size_t p = 0; p < mesh.primitives.size(); ++p) {
    const tinygltf::Primitive& prim = mesh.primitives[p];
    const std::string where = absl::StrCat("meshes[", index, "].primitives[", p, "]");
    if (PrimitiveTriangles(prim.mode, 3) == 0) continue;  // points or lines: not drawn
    size_t vertices = 0;
    if (prim.indices >= 0) {
      auto indices = AccessorReader::Open(model, prim.indices, where + ".indices");
      if (!indices.ok()) return indices.status();
      vertices = indices->count();
    } else {
      const auto position = prim.attributes.find("POSITION");
      if (position == prim.attributes.end())
        return Invalid(where + ".attributes", "has no POSITION");
      auto positions =
          AccessorReader::Open(model, position->second, where + ".attributes.POSITION");
      if (!positions.ok()) return positions.status();
      vertices = positions->count();
    }
    triangles = SaturatingAdd(triangles, PrimitiveTriangles(prim.mode, vertices));
  }
  return triangles;
}

}  // namespace

uint64_t PrimitiveTriangles(int mode, size_t vertices) {
  switch (mode) {
    case -1:
    case TINYGLTF_MODE_TRIANGLES:
      return vertices / 3;
    case TINYGLTF_MODE_TRIANGLE_STRIP:
    case TINYGLTF_MODE_TRIANGLE_FAN:
      return vertices >= 3 ? vertices - 2 : 0;
    default:
      return 0;
  }
}

absl::StatusOr<uint64_t> CountTriangles(const tinygltf::Model& model, std::span<const int> nodes) {
  std::vector<std::optional<uint64_t>> per_mesh(model.meshes.size());
  uint64_t total = 0;
  for (const int node : nodes) {
    const int mesh = model.nodes[node].mesh;
    if (mesh < 0) continue;
    if (mesh >= static_cast<int>(model.meshes.size()))
      return Invalid(absl::StrCat("nodes[", node, "].mesh"),
                     absl::StrCat("mesh ", mesh, " does not exist"));
    if (!per_mesh[mesh]) {
      auto triangles = MeshTriangles(model, mesh);
      if (!triangles.ok()) return triangles.status();
      per_mesh[mesh] = *triangles;
    }
    total = SaturatingAdd(total, *per_mesh[mesh]);
  }
  return total;
}

}  // namespace aperture
