#include "scene_request.h"

#include <optional>
#include <set>

#include "absl/strings/str_cat.h"
#include "content_hash.h"
#include "frame/camera_proto.h"
#include "google/protobuf/io/coded_stream.h"
#include "google/protobuf/io/zero_copy_stream_impl_lite.h"
#include "scene/builtin_scenes.h"
#include "scene/scene_builder.h"

namespace aperture {
namespace {

std::string DeterministicBytes(const v1::LoadSceneRequest& request) {
  std::string bytes;
  google::protobuf::io::StringOutputStream stream(&bytes);
  google::protobuf::io::CodedOutputStream coded(&stream);
  coded.SetSerializationDeterministic(true);
  request.SerializeToCodedStream(&coded);
  coded.Trim();
  return bytes;
}

}  // namespace

std::string SceneRequestId(const v1::LoadSceneRequest& request) {
  return Sha256Hex(DeterministicBytes(request));
}

absl::StatusOr<LoadedScene> BuildSceneFromRequest(const v1::LoadSceneRequest& request,
                                                  const TextureStore& textures,
                                                  const SceneLimits& limits,
                                                  std::function<bool()> stop,
                                                  const AdmitScene& admit) {
  v1::Scene scene = request.scene();
  std::optional<v1::Camera> default_camera;
  if (!request.builtin_scene().empty()) {
    if (request.has_scene() || !request.texture_sha256().empty())
      return absl::InvalidArgumentError(
          "builtin_scene: give either a built-in scene's name or a scene, not both");
    auto builtin = FindBuiltinScene(request.builtin_scene());
    if (!builtin.ok())
      return absl::InvalidArgumentError(
          absl::StrCat("builtin_scene: ", builtin.status().message()));
    scene = std::move(builtin->scene);
    default_camera = CameraToProto(builtin->camera);
  }
  // Before any texture is fetched (each is copied into the scene): the engine checks the rest.
  if (limits.textures > 0 && static_cast<uint64_t>(scene.textures_size()) > limits.textures)
    return absl::InvalidArgumentError(absl::StrCat("scene.textures: the scene has ",
                                                   scene.textures_size(), ", above the limit of ",
                                                   limits.textures, " textures per scene"));
  std::set<std::string> referenced;
  for (int i = 0; i < scene.textures_size(); ++i) {
    v1::Texture& texture = *scene.mutable_textures(i);
    const std::string field = absl::StrCat("scene.textures[", i, "] ('", texture.id(), "')");
    if (texture.source_case() == v1::Texture::kFile)
      return absl::InvalidArgumentError(absl::StrCat(
          field,
          ".file: the server reads no client paths; upload the image and name its hash "
          "in texture_sha256"));
    auto ref = request.texture_sha256().find(texture.id());
    if (ref == request.texture_sha256().end()) continue;
    referenced.insert(texture.id());
    if (texture.source_case() != v1::Texture::SOURCE_NOT_SET)
      return absl::InvalidArgumentError(
          absl::StrCat(field, " has an inline source and a texture_sha256 entry; give one"));
    if (!IsSha256Hex(ref->second))
      return absl::InvalidArgumentError(
          absl::StrCat("texture_sha256['", texture.id(), "'] must be 64 lowercase hex digits"));
    auto bytes = textures.Get(ref->second);
    if (!bytes.ok())
      return absl::NotFoundError(
          absl::StrCat("texture_sha256['", texture.id(), "']: ", bytes.status().message()));
    texture.set_encoded(**bytes);
  }
  for (const auto& [id, sha256] : request.texture_sha256())
    if (!referenced.count(id))
      return absl::InvalidArgumentError(
          absl::StrCat("texture_sha256['", id, "'] names no texture of the scene"));

  if (admit) {
    auto memory = EstimateSceneMemory(scene);
    if (!memory.ok())
      return absl::InvalidArgumentError(absl::StrCat("scene.", memory.status().message()));
    if (auto admitted = admit(*memory); !admitted.ok()) return admitted;
  }
  // Tables of aniso materials and decoded packed textures go to (or come from) the shared store.
  SceneBuildOptions options;
  options.store = textures.shared();
  options.limits = limits;
  options.stop = std::move(stop);
  auto built = BuildScene(scene, options);
  if (!built.ok()) return built.status();
  return LoadedScene{SceneRequestId(request), std::make_shared<const Scene>(*std::move(built)),
                     std::move(default_camera)};
}

}  // namespace aperture
