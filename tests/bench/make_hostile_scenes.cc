// Writes the hostile-content scenes of tests/support/hostile_scenes.h as scene files (proto3
// JSON) into a folder, for scripts/bench-hostile.sh:
//   coplanar.json, coplanar-spread.json, coplanar-layers.json, stacked.json, stacked-spread.json,
//   copies.json, and dag40.gltf (a glTF model whose 40 nodes each list the next twice: 2^40
//   triangles if it were expanded, which glTF forbids)
//
//   make_hostile_scenes OUT_DIR
#include <google/protobuf/util/json_util.h>

#include <cstdio>
#include <fstream>
#include <string>

#include "support/gltf_test_models.h"
#include "support/hostile_scenes.h"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: make_hostile_scenes OUT_DIR\n");
    return 2;
  }
  using namespace aperture::testing;
  const std::pair<const char*, aperture::v1::Scene> scenes[] = {
      {"coplanar", CoplanarCrowdScene(false)},      {"coplanar-spread", CoplanarCrowdScene(true)},
      {"coplanar-layers", CoplanarLayersScene()},   {"stacked", StackedLayersScene(false)},
      {"stacked-spread", StackedLayersScene(true)}, {"copies", CopiesScene(10000)}};
  for (const auto& [name, scene] : scenes) {
    std::string json;
    if (!google::protobuf::util::MessageToJsonString(scene, &json).ok()) return 1;
    const std::string path = std::string(argv[1]) + "/" + name + ".json";
    std::ofstream out(path);
    out << json;
    if (!out) {
      std::fprintf(stderr, "make_hostile_scenes: cannot write %s\n", path.c_str());
      return 1;
    }
  }
  const std::string dag = std::string(argv[1]) + "/dag40.gltf";
  std::ofstream out(dag);
  out << DuplicatedChildDag(40);
  if (!out) {
    std::fprintf(stderr, "make_hostile_scenes: cannot write %s\n", dag.c_str());
    return 1;
  }
  return 0;
}
