// The triangles a glTF import will make, counted from the accessors' counts before any vertex is
// read or any polygon allocated: a mesh placed by many nodes, or a strip of a few bytes per
// triangle, can ask for far more polygons than the file's size suggests.
#pragma once

#include <tiny_gltf.h>

#include <cstddef>
#include <cstdint>
#include <span>

#include "absl/status/statusor.h"

namespace aperture {

// The triangles of a primitive of `mode` (-1: the default, triangles) over `vertices` vertices
// (its indices, else its positions), glTF 2.0 "3.7.2.1": a list makes n / 3, a strip or fan
// n - 2; points and lines none.
uint64_t PrimitiveTriangles(int mode, size_t vertices);

// The triangles of `nodes`' meshes, each mesh counted once for every node that places it
// (degenerate ones included: they are dropped only once read). Each accessor counted is opened,
// so an element count beyond its buffer is refused here, naming it; so is a mesh that does not
// exist. Saturates at UINT64_MAX.
absl::StatusOr<uint64_t> CountTriangles(const tinygltf::Model& model, std::span<const int> nodes);

}  // namespace aperture
