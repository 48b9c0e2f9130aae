#include "scene_upload.h"

#include <google/protobuf/util/json_util.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string_view>

#include "absl/flags/flag.h"
#include "absl/strings/str_cat.h"
#include "channel.h"
#include "client_flags.h"
#include "exit_status.h"
#include "gltf_import.h"
#include "grpc_status.h"
#include "texture_upload.h"

namespace aperture {
namespace {

absl::StatusOr<std::string> ReadFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in)
    return absl::NotFoundError(absl::StrCat("cannot read ", path, ": ", std::strerror(errno)));
  std::ostringstream content;
  content << in.rdbuf();
  return std::move(content).str();
}

absl::StatusOr<v1::Scene> ReadScene(const std::string& argument, std::vector<GltfCamera>* cameras) {
  if (IsGltfPath(argument)) {  // a glTF model: its images are uploaded as a scene file's are
    auto model = ImportGltf(argument);
    if (!model.ok()) return model.status();
    for (const std::string& note : model->notes)
      std::fprintf(stderr, "aperture: %s: %s\n", argument.c_str(), note.c_str());
    *cameras = std::move(model->cameras);
    return std::move(model->scene);
  }
  auto json = ReadFile(argument);
  if (!json.ok()) return json.status();
  v1::Scene scene;
  google::protobuf::util::JsonParseOptions options;
  options.ignore_unknown_fields = false;
  if (auto s = google::protobuf::util::JsonStringToMessage(*json, &scene, options); !s.ok())
    return absl::InvalidArgumentError(absl::StrCat(argument, ": ", std::string(s.message())));
  // glTF models it places become meshes here: the server never reads the client's files.
  std::vector<std::string> notes;
  if (auto s = ExpandModels(scene, std::filesystem::path(argument).parent_path().string(),
                            absl::GetFlag(FLAGS_allow_any_path), &notes);
      !s.ok())
    return absl::Status(s.code(), absl::StrCat(argument, ": ", s.message()));
  for (const std::string& note : notes)
    std::fprintf(stderr, "aperture: %s: %s\n", argument.c_str(), note.c_str());
  return scene;
}

absl::StatusOr<SceneOnServer> Load(v1::Render::Stub& stub, const v1::LoadSceneRequest& request,
                                   SceneOnServer result) {
  grpc::ClientContext context;
  context.set_deadline(DeadlineIn(120));
  v1::LoadSceneResponse response;
  if (auto s = FromGrpcStatus(stub.LoadScene(&context, request, &response), "LoadScene"); !s.ok())
    return s;
  result.scene_id = response.scene_id();
  result.polygons = response.polygons();
  if (response.has_default_camera()) result.default_camera = response.default_camera();
  result.objects.assign(response.objects().begin(), response.objects().end());
  return result;
}

// The file a scene file's texture names: relative to the scene file's folder, and (unless
// `allow_any_path`) inside it once every symlink is resolved, so a scene file cannot make the
// client upload /etc/passwd or ~/.ssh to a server.
absl::StatusOr<std::filesystem::path> TexturePath(const std::string& scene_file, int index,
                                                  const v1::Texture& texture, bool allow_any_path) {
  namespace fs = std::filesystem;
  const fs::path folder = fs::path(scene_file).parent_path();
  const fs::path named = texture.file();
  const fs::path path = named.is_absolute() ? named : folder / named;
  if (allow_any_path) return path;
  std::error_code error;
  const fs::path real_folder = fs::weakly_canonical(folder.empty() ? "." : folder, error);
  const fs::path real = fs::weakly_canonical(path, error);
  if (error) return absl::NotFoundError(absl::StrCat("cannot resolve ", path.string()));
  const fs::path inside = real.lexically_relative(real_folder);
  if (inside.empty() || *inside.begin() == "..")
    return absl::PermissionDeniedError(absl::StrCat(
        scene_file, ": textures[", index, "] ('", texture.id(), "').file '", texture.file(),
        "' resolves to ", real.string(), ", outside the scene file's folder ", real_folder.string(),
        "; give --allow-any-path to upload it anyway"));
  return path;
}

}  // namespace

bool IsBuiltinScene(const std::string& argument) {
  if (argument == "demo" || argument == "airport" || argument == "night" ||
      argument == "night-by-day" ||
      argument == "triangles" || argument == "skewed")
    return true;
  // tris-N, slivers-N: the server checks N's range and names it when it is out of range.
  for (const std::string_view prefix : {std::string_view("tris-"), std::string_view("slivers-")})
    if (argument.size() > prefix.size() && argument.compare(0, prefix.size(), prefix) == 0 &&
        argument.find_first_not_of("0123456789", prefix.size()) == std::string::npos)
      return true;
  return false;
}

absl::StatusOr<SceneOnServer> LoadSceneOnServer(v1::Render::Stub& stub,
                                                const std::string& scene_argument) {
  SceneOnServer result;
  v1::LoadSceneRequest request;
  if (IsBuiltinScene(scene_argument)) {
    request.set_builtin_scene(scene_argument);  // the server builds it
    return Load(stub, request, result);
  }
  // What the scene file, its textures and models say is the command's input: bad, it exits 2.
  auto scene = ReadScene(scene_argument, &result.model_cameras);
  if (!scene.ok()) return InputError(scene.status());
  const std::filesystem::path base = std::filesystem::path(scene_argument).parent_path();
  for (int i = 0; i < scene->textures_size(); ++i) {
    v1::Texture& texture = *scene->mutable_textures(i);
    std::string bytes;
    if (texture.source_case() == v1::Texture::kFile) {
      auto path = TexturePath(scene_argument, i, texture, absl::GetFlag(FLAGS_allow_any_path));
      if (!path.ok()) return InputError(path.status());
      auto read = ReadFile(path->string());
      if (!read.ok()) return InputError(read.status());
      bytes = *std::move(read);
    } else if (texture.source_case() == v1::Texture::kEncoded) {
      bytes = texture.encoded();
    } else {
      continue;  // procedural: travels inside the scene
    }
    auto uploaded = EnsureTextureUploaded(stub, bytes);
    if (!uploaded.ok()) return uploaded.status();
    ++(uploaded->sent ? result.textures_sent : result.textures_skipped);
    texture.clear_source();
    (*request.mutable_texture_sha256())[texture.id()] = uploaded->sha256;
  }
  if (scene->name().empty()) scene->set_name(scene_argument);
  *request.mutable_scene() = *std::move(scene);
  return Load(stub, request, result);
}

}  // namespace aperture
