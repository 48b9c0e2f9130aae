// The JSON structure of a glTF file, checked before tinygltf reads it. tinygltf (2.7) passes over
// a field of the wrong type without a word (`primitives` an object: a mesh of nothing, imported
// as an empty model), keeps an index array up to its first non-integer, casts integers to int
// (node 4294967296 becomes node 0), and turns `extras` and `extensions` into its own values
// recursively, which a deeply nested array overflows the stack with. So every field the importer
// reads is checked here for its JSON type and range, required ones for their presence, and no
// value may nest deeper than kMaxGltfJsonNesting. Fields the importer does not read are not
// checked (a wrong `normalTexture.scale` is ignored, as the normal texture is).
#pragma once

#include <cstdint>
#include <span>
#include <string_view>

#include "absl/status/status.h"
#include "absl/status/statusor.h"

namespace aperture {

// Arrays and objects inside each other, the document itself level 1. glTF's own structure needs 8
// (materials[i].pbrMetallicRoughness.baseColorTexture.extensions.KHR_texture_transform.offset);
// the rest is room for applications' `extras`.
inline constexpr int kMaxGltfJsonNesting = 64;

// `json`: the text of a .gltf, or the JSON chunk of a .glb. Errors name the path in the file:
// "meshes[0].primitives: expected an array".
absl::Status CheckGltfJsonStructure(std::string_view json);

// The JSON chunk of a .glb file (glTF 2.0, "4.4 Binary glTF Layout"): the first chunk, of type
// JSON, within the file.
absl::StatusOr<std::string_view> GlbJsonChunk(std::span<const uint8_t> bytes);

}  // namespace aperture
