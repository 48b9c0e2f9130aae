// A scene's textures from their proto sources (image files, encoded images, packed .apv maps,
// checkerboards), and the sampler each filter mode reads them with.
#pragma once

#include <memory>
#include <optional>
#include <string>

#include "absl/status/statusor.h"
#include "aperture/v1/scene.pb.h"
#include "scene/scene.h"
#include "scene/scene_builder.h"

namespace aperture {

// Texture `t` (named `where` in errors) decoded or built, its seed 000 tables and decoded packed
// maps through options.store when there is one; relative files against options.base_dir.
absl::StatusOr<std::shared_ptr<const SceneTexture>> BuildSceneTexture(
    const v1::Texture& t, const std::string& where, const SceneBuildOptions& options);

// The engine's filter for a proto filter value; nullopt for TEXTURE_FILTER_DEFAULT and for
// values this build does not know. Here rather than in frame/ with the request's conversions: a
// scene's materials name their filter too (scene_builder), and scene/ comes before frame/.
std::optional<FilterMode> FilterModeFromProto(int filter);

}  // namespace aperture
