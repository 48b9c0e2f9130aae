#include "scene/scene_file.h"

#include <gtest/gtest.h>

#include <string>

#include "scene/scene_builder.h"

namespace aperture {
namespace {

const std::string kScenes = std::string(APERTURE_TEST_DATA) + "/scenes/";

TEST(SceneFile, LoadsTheExampleScene) {
  auto scene = LoadSceneFile(kScenes + "two_quads.json");
  ASSERT_TRUE(scene.ok()) << scene.status();
  EXPECT_EQ(scene->name, "two-quads");
  // The concave L-shape is triangulated into 4 triangles; the ground stays one quad.
  EXPECT_EQ(scene->polygons.size(), 5u);
  EXPECT_EQ(scene->textures.size(), 1u);
  EXPECT_NEAR(scene->fog_density, 0.001, 1e-15);
}

TEST(SceneFile, JsonRoundTripKeepsTheScene) {
  auto proto = ReadSceneFile(kScenes + "two_quads.json");
  ASSERT_TRUE(proto.ok());
  auto again = ParseSceneJson(SceneToJson(*proto));
  ASSERT_TRUE(again.ok()) << again.status();
  EXPECT_EQ(again->SerializeAsString(), proto->SerializeAsString());
}

struct BadScene {
  const char* name;
  std::string json;
  const char* message;  // must appear in the error
};

std::string Quad(const std::string& first_vertex) {
  return R"({"meshes": [{"id": "m", "polygons": [{"vertices": [)" + first_vertex +
         R"(, {"x": 1, "y": 0, "z": 0}, {"x": 1, "y": 0, "z": 1}, {"x": 0, "y": 0, "z": 1}]}]}]})";
}

class BadSceneTest : public ::testing::TestWithParam<BadScene> {};

TEST_P(BadSceneTest, FailsWithAMessageNamingTheProblem) {
  const BadScene& bad = GetParam();
  absl::Status status;
  auto proto = ParseSceneJson(bad.json);
  if (!proto.ok()) {
    status = proto.status();
  } else {
    SceneBuildOptions options;
    options.base_dir = kScenes;
    status = BuildScene(*proto, options).status();
  }
  ASSERT_FALSE(status.ok()) << bad.name;
  EXPECT_NE(status.message().find(bad.message), std::string::npos)
      << bad.name << ": " << status.message();
}

INSTANTIATE_TEST_SUITE_P(
    Scenes, BadSceneTest,
    ::testing::Values(
        BadScene{"syntax", R"({"name": "x", )", "scene JSON is invalid"},
        BadScene{"unknown field", R"({"name": "x", "colour": 1})", "colour"},
        BadScene{"NaN vertex", Quad(R"({"x": "NaN", "y": 0, "z": 0})"), "vertices[0]"},
        BadScene{"infinite vertex", Quad(R"({"x": "Infinity", "y": 0, "z": 0})"),
                 "NaN or infinite"},
        BadScene{"two vertices",
                 R"({"meshes": [{"id": "m", "polygons": [{"vertices": [{"x": 0}, {"x": 1}]}]}]})",
                 "needs at least 3"},
        BadScene{"collinear", R"({"meshes": [{"id": "m", "polygons": [{"vertices": [
                   {"x": 0}, {"x": 1}, {"x": 2}]}]}]})",
                 "degenerate"},
        BadScene{"coincident", R"({"meshes": [{"id": "m", "polygons": [{"vertices": [
                   {"x": 1}, {"x": 1}, {"x": 1}, {"y": 2}]}]}]})",
                 "fewer than 3 distinct"},
        BadScene{"not planar", R"({"meshes": [{"id": "m", "polygons": [{"vertices": [
                   {"x": 0}, {"x": 1}, {"x": 1, "z": 1}, {"y": 1, "z": 1}]}]}]})",
                 "not planar"},
        // A pentagram turns left at every vertex but crosses itself.
        BadScene{"pentagram", R"({"meshes": [{"id": "m", "polygons": [{"vertices": [
                   {"x": 1, "z": 0}, {"x": -0.809017, "z": 0.587785},
                   {"x": 0.309017, "z": -0.951057}, {"x": 0.309017, "z": 0.951057},
                   {"x": -0.809017, "z": -0.587785}]}]}]})",
                 "meshes[0].polygons[0]: polygon is self-intersecting: edges"},
        BadScene{"uneven bow tie", R"({"meshes": [{"id": "m", "polygons": [{"vertices": [
                   {"x": 0}, {"x": 3, "z": 2}, {"x": 3}, {"z": 1}]}]}]})",
                 "self-intersecting"},
        BadScene{"huge coordinate", R"({"meshes": [{"id": "m", "polygons": [{"vertices": [
                   {"x": 0}, {"x": 1e300}, {"y": 1}]}]}]})",
                 "coordinates are limited to +-1e8 m"},
        BadScene{"missing texture file",
                 R"({"textures": [{"id": "t", "file": "no_such_file.png"}]})", "does not exist"},
        BadScene{"texture without source", R"({"textures": [{"id": "t"}]})", "no source"},
        BadScene{"unknown texture id", R"({"materials": [{"id": "m", "texture_id": "nope"}]})",
                 "'nope'"},
        BadScene{"unknown material id",
                 R"({"meshes": [{"id": "m", "material_id": "nope", "polygons": [{"vertices": [
                   {"x": 0}, {"x": 1}, {"y": 1}]}]}]})",
                 "material_id 'nope'"},
        BadScene{"unknown mesh id", R"({"objects": [{"mesh_id": "nope"}]})", "mesh_id 'nope'"},
        BadScene{"zero scale", R"({"meshes": [{"id": "m"}], "objects": [{"mesh_id": "m",
                   "transform": {"scale": {"x": 0, "y": 1, "z": 1}}}]})",
                 "scale"},
        BadScene{"negative fog", R"({"fog": {"density": -1}})", "fog.density"},
        BadScene{"huge checkerboard",
                 R"({"textures": [{"id": "t", "checkerboard": {"size": 100000}}]})", "above 8192"},
        BadScene{"uv count", R"({"meshes": [{"id": "m", "polygons": [{"vertices": [
                   {"x": 0}, {"x": 1}, {"y": 1}], "uvs": [{"u": 0}]}]}]})",
                 "1 uvs for 3 vertices"},
        BadScene{"duplicate material", R"({"materials": [{"id": "a"}, {"id": "a"}]})",
                 "duplicate material id"}),
    [](const ::testing::TestParamInfo<BadScene>& param) {
      std::string name = param.param.name;
      for (char& c : name)
        if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
      return name;
    });

TEST(SceneFile, MissingFileIsNotFound) {
  auto scene = LoadSceneFile(kScenes + "does_not_exist.json");
  ASSERT_FALSE(scene.ok());
  EXPECT_NE(scene.status().message().find("does_not_exist.json"), std::string::npos);
}

TEST(SceneFile, ErrorsNameTheFileAndThePolygon) {
  auto proto = ParseSceneJson(Quad(R"({"x": "NaN", "y": 0, "z": 0})"));
  ASSERT_TRUE(proto.ok());
  auto scene = BuildScene(*proto);
  ASSERT_FALSE(scene.ok());
  EXPECT_NE(scene.status().message().find("meshes[0].polygons[0].vertices[0]"), std::string::npos)
      << scene.status().message();
}

}  // namespace
}  // namespace aperture
