// KHR_lights_punctual in glTF models: point and spot lights become light points at their nodes'
// world origins (a spot's outer cone its lobe about the node's -z), directional and dark lights
// are noted, bad references are refused naming the path, and a scene file's model carries its
// lights on each object that places it.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "absl/strings/str_join.h"
#include "gltf_import.h"
#include "support/gltf_import_helpers.h"
#include "support/gltf_test_models.h"

namespace aperture {
namespace {

using testing::ErrorOf;
using testing::ImportJson;

// A model whose `nodes` may name lights of `lights` (the extension's array).
std::string WithLights(const std::string& nodes, const std::string& lights) {
  std::string file = testing::GltfFile(nodes, R"([{"nodes": [0]}])");
  const std::string extension = R"({"extensionsUsed": ["KHR_lights_punctual"], )"
                                R"("extensions": {"KHR_lights_punctual": {"lights": )" +
                                lights + "}}, ";
  return extension + file.substr(1);
}

TEST(GltfLights, PointAndSpotLightsBecomeLightPointsAtTheirNodes) {
  // Node 0 moves its children by (10, 0, 0); node 1 holds the point light 2 m up, node 2 the spot,
  // turned a quarter about x so that its -z looks up (+y).
  const double s = std::sqrt(0.5);
  const std::string nodes =
      R"([{"translation": [10, 0, 0], "children": [1, 2, 3]},
          {"translation": [0, 2, 0], "extensions": {"KHR_lights_punctual": {"light": 0}}},
          {"rotation": [)" +
      std::to_string(s) + ", 0, 0, " + std::to_string(s) +
      R"(], "extensions": {"KHR_lights_punctual": {"light": 1}}},
          {"mesh": 0}])";
  const std::string lights =
      R"([{"type": "point", "name": "lamp", "color": [1, 0.5, 0.25], "intensity": 120},
          {"type": "spot", "intensity": 900, "spot": {"outerConeAngle": 0.5}}])";
  auto model = ImportJson(WithLights(nodes, lights));
  ASSERT_TRUE(model.ok()) << model.status();
  ASSERT_EQ(model->scene.lights_size(), 2);
  const v1::LightPoint& point = model->scene.lights(0);
  EXPECT_DOUBLE_EQ(point.position().x(), 10);
  EXPECT_DOUBLE_EQ(point.position().y(), 2);
  EXPECT_DOUBLE_EQ(point.intensity_cd(), 120);
  EXPECT_FLOAT_EQ(point.color().g(), 0.5f);
  EXPECT_EQ(point.group(), "lamp");
  EXPECT_FALSE(point.has_lobe());
  const v1::LightPoint& spot = model->scene.lights(1);
  EXPECT_DOUBLE_EQ(spot.intensity_cd(), 900);
  EXPECT_EQ(spot.group(), "light1");
  ASSERT_TRUE(spot.has_lobe());
  EXPECT_NEAR(spot.lobe().axis().x(), 0, 1e-6);
  EXPECT_NEAR(spot.lobe().axis().y(), 1, 1e-6);
  EXPECT_NEAR(spot.lobe().axis().z(), 0, 1e-6);
  EXPECT_NEAR(spot.lobe().horizontal_deg(), 0.5 * 180 / M_PI, 1e-9);
  EXPECT_NEAR(spot.lobe().vertical_deg(), 0.5 * 180 / M_PI, 1e-9);
  for (const std::string& note : model->notes)
    EXPECT_EQ(note.find("KHR_lights_punctual"), std::string::npos) << note;
}

TEST(GltfLights, DirectionalDarkAndRangedLightsAreNoted) {
  const std::string nodes =
      R"([{"children": [1, 2, 3, 4]},
          {"extensions": {"KHR_lights_punctual": {"light": 0}}},
          {"extensions": {"KHR_lights_punctual": {"light": 1}}},
          {"extensions": {"KHR_lights_punctual": {"light": 2}}},
          {"mesh": 0}])";
  const std::string lights =
      R"([{"type": "directional", "intensity": 3},
          {"type": "point", "intensity": 0},
          {"type": "point", "intensity": 5, "range": 40}])";
  auto model = ImportJson(WithLights(nodes, lights));
  ASSERT_TRUE(model.ok()) << model.status();
  EXPECT_EQ(model->scene.lights_size(), 1);
  const std::string notes = absl::StrJoin(model->notes, "\n");
  EXPECT_NE(notes.find("1 directional lights ignored"), std::string::npos) << notes;
  EXPECT_NE(notes.find("1 lights of zero intensity skipped"), std::string::npos) << notes;
  EXPECT_NE(notes.find("1 lights' ranges ignored"), std::string::npos) << notes;
}

TEST(GltfLights, BadLightsAreRefusedNamingThePath) {
  const std::string one_light = R"([{"type": "point", "intensity": 5}])";
  EXPECT_EQ(
      ErrorOf(ImportJson(WithLights(
          R"([{"children": [1]}, {"mesh": 0, "extensions": {"KHR_lights_punctual": {"light": 3}}}])",
          one_light))),
      "nodes[1].extensions.KHR_lights_punctual.light: light 3 does not exist (1 lights)");
  EXPECT_EQ(ErrorOf(ImportJson(
                WithLights(R"([{"mesh": 0, "extensions": {"KHR_lights_punctual": {"light": 0}}}])",
                           R"([{"type": "area", "intensity": 5}])"))),
            "extensions.KHR_lights_punctual.lights[0].type: 'area' is not point, spot or "
            "directional");
  EXPECT_EQ(ErrorOf(ImportJson(WithLights(
                R"([{"mesh": 0, "extensions": {"KHR_lights_punctual": {"light": 0}}}])",
                R"([{"type": "spot", "intensity": 5, "spot": {"outerConeAngle": 2}}])"))),
            "extensions.KHR_lights_punctual.lights[0].spot.outerConeAngle: must be in (0, pi/2]");
  EXPECT_EQ(ErrorOf(ImportJson(
                WithLights(R"([{"mesh": 0, "extensions": {"KHR_lights_punctual": {"light": 0}}}])",
                           R"([{"type": "point", "intensity": -1}])"))),
            "extensions.KHR_lights_punctual.lights[0].intensity: must be a finite number >= 0 "
            "(candela)");
}

// A scene file's model with a light, placed by a named and an unnamed object: each carries the
// light in the model's frame (the unnamed one is given a name to carry it by).
TEST(GltfLights, EachObjectPlacingAModelCarriesItsLights) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() /
                                    ("aperture_gltf_lights_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "mast.gltf") << WithLights(
      R"([{"mesh": 0, "children": [1]}, {"translation": [0, 12, 0], "extensions": {"KHR_lights_punctual": {"light": 0}}}])",
      R"([{"type": "point", "name": "top", "intensity": 32, "color": [1, 0, 0]}])");
  v1::Scene scene;
  v1::Model* model = scene.add_models();
  model->set_id("mast");
  model->set_file("mast.gltf");
  v1::Object* named = scene.add_objects();
  named->set_model_id("mast");
  named->set_name("north mast");
  scene.add_objects()->set_model_id("mast");
  const absl::Status expanded = ExpandModels(scene, dir.string(), false, nullptr);
  std::filesystem::remove_all(dir);
  ASSERT_TRUE(expanded.ok()) << expanded;
  ASSERT_EQ(scene.lights_size(), 2);
  EXPECT_EQ(scene.lights(0).object(), "north mast");
  EXPECT_EQ(scene.objects(1).name(), "mast#1");
  EXPECT_EQ(scene.lights(1).object(), "mast#1");
  for (const v1::LightPoint& light : scene.lights()) {
    EXPECT_DOUBLE_EQ(light.position().y(), 12);
    EXPECT_EQ(light.group(), "mast/top");
  }
}

}  // namespace
}  // namespace aperture
