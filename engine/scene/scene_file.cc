#include "scene/scene_file.h"

#include <google/protobuf/util/json_util.h>
#include <spdlog/spdlog.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "absl/strings/str_cat.h"
#include "gltf_import.h"
#include "scene/scene_builder.h"

namespace aperture {

absl::StatusOr<v1::Scene> ParseSceneJson(const std::string& json) {
  v1::Scene scene;
  google::protobuf::util::JsonParseOptions options;
  options.ignore_unknown_fields = false;
  auto status = google::protobuf::util::JsonStringToMessage(json, &scene, options);
  if (!status.ok())
    return absl::InvalidArgumentError(
        absl::StrCat("scene JSON is invalid: ", std::string(status.message())));
  return scene;
}

absl::StatusOr<v1::Scene> ReadSceneFile(const std::string& path, std::vector<GltfCamera>* cameras) {
  if (IsGltfPath(path)) {
    auto model = ImportGltf(path);
    if (!model.ok()) return model.status();
    for (const std::string& note : model->notes) spdlog::warn("{}: {}", path, note);
    if (cameras != nullptr) *cameras = std::move(model->cameras);
    return std::move(model->scene);
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) return absl::NotFoundError(absl::StrCat("cannot open scene file '", path, "'"));
  std::ostringstream text;
  text << in.rdbuf();
  auto scene = ParseSceneJson(text.str());
  if (!scene.ok())
    return absl::InvalidArgumentError(absl::StrCat(path, ": ", scene.status().message()));
  // The glTF models it places, read from files next to it (the user's own: any path).
  std::vector<std::string> notes;
  if (auto s = ExpandModels(*scene, std::filesystem::path(path).parent_path().string(),
                            /*allow_any_path=*/true, &notes);
      !s.ok())
    return absl::Status(s.code(), absl::StrCat(path, ": ", s.message()));
  for (const std::string& note : notes) spdlog::warn("{}: {}", path, note);
  return scene;
}

std::string SceneToJson(const v1::Scene& scene) {
  std::string json;
  google::protobuf::util::JsonPrintOptions options;
  options.add_whitespace = true;
  options.preserve_proto_field_names = true;
  (void)google::protobuf::util::MessageToJsonString(scene, &json, options);
  return json;
}

absl::StatusOr<Scene> LoadSceneFile(const std::string& path,
                                    std::shared_ptr<const SharedStore> store) {
  auto proto = ReadSceneFile(path);
  if (!proto.ok()) return proto.status();
  return BuildSceneFile(*proto, path, std::move(store));
}

absl::StatusOr<Scene> BuildSceneFile(const v1::Scene& proto, const std::string& path,
                                     std::shared_ptr<const SharedStore> store) {
  SceneBuildOptions options;
  options.base_dir = std::filesystem::path(path).parent_path().string();
  options.store = std::move(store);
  auto scene = BuildScene(proto, options);
  if (!scene.ok())
    return absl::Status(scene.status().code(), absl::StrCat(path, ": ", scene.status().message()));
  if (scene->name.empty()) scene->name = std::filesystem::path(path).stem().string();
  return scene;
}

}  // namespace aperture
