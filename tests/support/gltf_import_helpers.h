// What the glTF import's unit tests share: a model imported from its JSON text, the message of a
// refusal, the triangles an import made.
#pragma once

#include <gtest/gtest.h>

#include <span>
#include <string>

#include "gltf_import.h"

namespace aperture::testing {

inline absl::StatusOr<ImportedModel> ImportJson(const std::string& json,
                                                const GltfImportOptions& options = {}) {
  return ImportGltfBytes(std::span(reinterpret_cast<const uint8_t*>(json.data()), json.size()),
                         /*binary=*/false, "/nonexistent", "test", options);
}

// The message of an import refused as INVALID_ARGUMENT (the test fails if it was not).
inline std::string ErrorOf(const absl::StatusOr<ImportedModel>& imported) {
  EXPECT_FALSE(imported.ok());
  EXPECT_EQ(imported.status().code(), absl::StatusCode::kInvalidArgument);
  return std::string(imported.status().message());
}

inline size_t Triangles(const ImportedModel& model) {
  size_t n = 0;
  for (const v1::Mesh& mesh : model.scene.meshes()) n += mesh.polygons_size();
  return n;
}

}  // namespace aperture::testing
