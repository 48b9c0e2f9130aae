// glTF 2.0 models in aperture-render: the import against an independent reading of the
// same file (tests/support/gltf_to_scene.py, the standard library's json and struct) pixel for
// pixel, the binary form with an embedded image, the file's cameras by name, and malformed
// models refused with the element named.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <vector>

#include "support/gltf_test_models.h"
#include "support/run_process.h"

namespace {

namespace fs = std::filesystem;
using Result = aperture::testing::ProcessResult;

const fs::path kSupport = fs::path(APERTURE_TESTS_DIR) / "support";

class GltfModel : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("aperture_gltf_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
    // The fixture made afresh by its generator (also kept in tests/data/models).
    const Result made = aperture::testing::RunProcess(
        "python3 " + (kSupport / "make_gltf_fixture.py").string() + " " + dir_.string());
    ASSERT_EQ(made.exit_code, 0) << made.output;
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string Path(const std::string& name) const { return (dir_ / name).string(); }

  Result Render(const std::string& scene, const std::string& args, const std::string& out) {
    return aperture::testing::RunProcess(std::string(APERTURE_RENDER_BIN) + " --scene " + scene +
                                         " --size 320x240 --float-pixels --compression none "
                                         "--nopreview --store none " +
                                         args + " -o " + Path(out));
  }
  std::vector<float> Pixels(const std::string& name) {
    auto in = OIIO::ImageInput::open(Path(name));
    EXPECT_TRUE(in) << name;
    if (!in) return {};
    std::vector<float> pixels(static_cast<size_t>(in->spec().image_pixels()) *
                              in->spec().nchannels);
    EXPECT_TRUE(in->read_image(0, 0, 0, -1, OIIO::TypeDesc::FLOAT, pixels.data()));
    return pixels;
  }
  // Renders `scene` and `reference` with the same flags; their pixels (`scene`'s) when they are
  // the same bits, else a failure and nothing.
  std::vector<float> RenderBothAndCompare(const std::string& scene, const std::string& reference,
                                          const std::string& args) {
    const Result a = Render(scene, args, "scene.exr"), b = Render(reference, args, "reference.exr");
    EXPECT_EQ(a.exit_code, 0) << a.output;
    EXPECT_EQ(b.exit_code, 0) << b.output;
    std::vector<float> pixels = Pixels("scene.exr");
    EXPECT_EQ(pixels.size(), 320u * 240 * 4);
    const std::vector<float> expected = Pixels("reference.exr");
    size_t differing = 0;
    for (size_t i = 0; i < std::min(pixels.size(), expected.size()); ++i)
      differing += pixels[i] != expected[i];
    EXPECT_EQ(differing, 0u) << scene << " against " << reference;
    EXPECT_EQ(pixels.size(), expected.size());
    if (differing != 0 || pixels.size() != expected.size() || pixels.empty()) return {};
    return pixels;
  }
  // The independent reading of a model (tests/support/gltf_to_scene.py) into reference.json.
  std::string Reference(const std::string& model, const std::string& options = "") {
    const Result ref =
        aperture::testing::RunProcess("python3 " + (kSupport / "gltf_to_scene.py").string() + " " +
                                      model + " " + options + " > " + Path("reference.json"));
    EXPECT_EQ(ref.exit_code, 0) << ref.output;
    return Path("reference.json");
  }

  // A malformed copy of hangar.gltf: every `from` in its JSON text replaced by `to`.
  std::string Malformed(const std::string& from, const std::string& to) {
    std::ifstream in(Path("hangar.gltf"));
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_NE(text.find(from), std::string::npos) << from;
    for (size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size()))
      text.replace(at, from.size(), to);
    std::ofstream(Path("bad.gltf")) << text;
    return Path("bad.gltf");
  }
  fs::path dir_;
};

constexpr char kCamera[] = "--camera 0,1.7,5,0,-5,0 --fov 50";

TEST_F(GltfModel, MatchesAnIndependentReadingPixelForPixel) {
  const std::vector<float> model =
      RenderBothAndCompare(Path("hangar.gltf"), Reference(Path("hangar.gltf")), kCamera);
  ASSERT_FALSE(model.empty());
  // Not a blank frame: the ground, the sky and the textured hall's many shades are there.
  std::set<float> reds;
  for (size_t i = 0; i < model.size(); i += 4) reds.insert(model[i]);
  EXPECT_GT(reds.size(), 50u);
}

TEST_F(GltfModel, TheBinaryFormAndDataUrisAreTheSameModel) {
  ASSERT_EQ(Render(Path("hangar.gltf"), kCamera, "gltf.exr").exit_code, 0);
  Result r = Render(Path("hangar.glb"), kCamera, "glb.exr");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(Pixels("gltf.exr"), Pixels("glb.exr"));
  r = Render(Path("hangar_embedded.gltf"), kCamera, "embedded.exr");  // data URIs
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(Pixels("gltf.exr"), Pixels("embedded.exr"));
}

TEST_F(GltfModel, TheFilesCamerasGoByNameAndTheFirstIsTheDefault) {
  // "gate": at (0, 1.7, 5), turned 5 degrees down about x, yfov 0.9 rad.
  const std::string numbers = "--camera 0,1.7,5,0,-5,0 --fov " + std::to_string(0.9 * 180 / M_PI);
  ASSERT_EQ(Render(Path("hangar.gltf"), numbers, "numbers.exr").exit_code, 0);
  ASSERT_EQ(Render(Path("hangar.gltf"), "--camera gate", "named.exr").exit_code, 0);
  ASSERT_EQ(Render(Path("hangar.gltf"), "", "default.exr").exit_code, 0);
  const std::vector<float> a = Pixels("numbers.exr"), b = Pixels("named.exr");
  ASSERT_EQ(a.size(), b.size());
  double worst = 0;
  for (size_t i = 0; i < a.size(); ++i) worst = std::max(worst, std::abs(double(a[i]) - b[i]));
  EXPECT_LT(worst, 1e-3);  // the angles round-trip through a rotation matrix
  EXPECT_EQ(Pixels("named.exr"), Pixels("default.exr"));

  const Result unknown = Render(Path("hangar.gltf"), "--camera tower", "x.exr");
  EXPECT_NE(unknown.exit_code, 0);
  EXPECT_NE(unknown.output.find("--camera 'tower' is neither X,Y,Z,YAW,PITCH,ROLL nor a camera"),
            std::string::npos)
      << unknown.output;
  EXPECT_NE(unknown.output.find("(gate)"), std::string::npos) << unknown.output;
}

// A scene file places models as objects, each instance with its own transform: the same pixels
// as the independent reading's triangles in one mesh placed by the same objects.
TEST_F(GltfModel, ASceneFilePlacesModelsAsObjects) {
  const std::string objects = R"([
    {"modelId": "hall", "transform": {"translation": {"x": -6, "y": 0, "z": -4}, "yawDeg": 20}},
    {"modelId": "hall_glb", "name": "second", "transform": {"translation": {"x": 5, "y": 0,
     "z": -12}, "yawDeg": -40, "scale": {"x": 0.5, "y": 0.5, "z": 0.5}}}])";
  std::ofstream(Path("apron.json")) << R"({"name": "apron", "models": [
      {"id": "hall", "file": "hangar.gltf"}, {"id": "hall_glb", "file": "hangar.glb"}],
    "objects": )" << objects << "}";
  std::ifstream in(Reference(Path("hangar.gltf"), "--as-mesh hall"));
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const size_t at = text.find("\"objects\": []");
  ASSERT_NE(at, std::string::npos);
  std::string placed = objects;
  for (size_t p = placed.find("hall_glb"); p != std::string::npos; p = placed.find("hall_glb"))
    placed.replace(p, 8, "hall");
  text.replace(at, 14, "\"objects\": " + placed);
  for (size_t p = text.find("modelId"); p != std::string::npos; p = text.find("modelId"))
    text.replace(p, 7, "meshId");
  std::ofstream(Path("reference.json")) << text;

  in.close();
  std::ofstream(Path("placed.json")) << text;
  EXPECT_FALSE(RenderBothAndCompare(Path("apron.json"), Path("placed.json"), kCamera).empty());

  // An object placing a model the scene does not have is refused, naming the object.
  std::ofstream(Path("unknown.json"))
      << R"({"objects": [{"modelId": "tower"}], "models": [{"id": "hall", "file": "hangar.gltf"}]})";
  const Result r = Render(Path("unknown.json"), kCamera, "x.exr");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.output.find("objects[0].model_id: 'tower' is not a model of the scene"),
            std::string::npos)
      << r.output;
}

TEST_F(GltfModel, WhatIsNotDrawnIsReportedOnce) {
  const std::string bad = Malformed("\"wrapS\": 10497", "\"wrapS\": 33071");
  const Result r = Render(bad, kCamera, "x.exr");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("1 textures with clamped or mirrored wrapping drawn repeated"),
            std::string::npos)
      << r.output;
}

// alphaMode BLEND with baseColorFactor's alpha, and MASK with alphaCutoff, as the independent
// reading maps them, pixel for pixel; and what each draws differs from the opaque model.
TEST_F(GltfModel, AlphaModesMatchTheIndependentReading) {
  const std::vector<float> opaque =
      RenderBothAndCompare(Path("hangar.gltf"), Reference(Path("hangar.gltf")), kCamera);
  ASSERT_FALSE(opaque.empty());
  // The hall's material, its factor's alpha 1 -> 0.5.
  const std::string hall =
      "\"pbrMetallicRoughness\": {\n    \"baseColorFactor\": [\n     0.9,\n     0.8,\n     0.7,\n  "
      "   "
      "1.0\n    ],";
  const std::string half = "\"pbrMetallicRoughness\": {\"baseColorFactor\": [0.9, 0.8, 0.7, 0.5],";
  for (const std::string mode :
       {"\"alphaMode\": \"BLEND\", ", "\"alphaMode\": \"MASK\", \"alphaCutoff\": 0.55, "}) {
    SCOPED_TRACE(mode);
    const std::string bad = Malformed(hall, mode + half);
    const std::vector<float> a = RenderBothAndCompare(bad, Reference(bad), kCamera);
    ASSERT_EQ(a.size(), opaque.size());
    EXPECT_NE(a, opaque);
  }
}

// Models of Debian's assimp-testmodels package (textures, embedded data,
// texture transforms, strips and fans, index types, a skin in its bind pose) against the
// independent reading, pixel for pixel; and the package's malformed models refused with messages.
const fs::path kPackage = "/usr/share/assimp/models/glTF2";

TEST_F(GltfModel, PackageModelsMatchTheIndependentReading) {
  ASSERT_TRUE(fs::exists(kPackage)) << "install assimp-testmodels (scripts/install-deps.sh)";
  const char* models[] = {
      "BoxTextured-glTF/BoxTextured.gltf",
      "BoxTextured-glTF-Embedded/BoxTextured.gltf",
      "BoxTexcoords-glTF/boxTexcoords.gltf",
      "textureTransform/TextureTransformTest.gltf",
      "glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_04.gltf",
      "glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_05.gltf",
      "glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_06.gltf",
      "glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_12.gltf",
      "simple_skin/simple_skin.gltf",
  };
  const std::string camera = "--camera 0.3,0.6,3,5,-10,0 --fov 50";
  for (const char* model : models) {
    SCOPED_TRACE(model);
    const std::string path = (kPackage / model).string();
    const std::vector<float> a = RenderBothAndCompare(path, Reference(path), camera);
    ASSERT_FALSE(a.empty());
    EXPECT_GT(*std::max_element(a.begin(), a.end()), 0.5f);  // the model is in view
  }
}

TEST_F(GltfModel, PackageMalformedModelsAreRefused) {
  ASSERT_TRUE(fs::exists(kPackage)) << "install assimp-testmodels (scripts/install-deps.sh)";
  const std::pair<const char*, const char*> cases[] = {
      {"IndexOutOfRange/IndexOutOfRange.gltf",
       "meshes[0].primitives[0].indices: index 255 out of range 0..23"},
      {"IndexOutOfRange/AllIndicesOutOfRange.gltf", "index 65535 out of range 0..23"},
      {"BoxWithInfinites-glTF-Binary/BoxWithInfinites.glb", "vertex 0 is NaN or infinite"},
      {"MissingBin/BoxTextured.gltf", "BoxTextured0.bin"},
      {"RecursiveNodes/RecursiveNodes.gltf", "nodes[0]: is its own ancestor"},
      {"draco/2CylinderEngine.gltf", "not a valid glTF file"},
  };
  for (const auto& [model, message] : cases) {
    SCOPED_TRACE(model);
    const Result r = Render((kPackage / model).string(), kCamera, "x.exr");
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find(message), std::string::npos) << r.output;
  }
}

struct BadModel {
  const char* what;
  const char* from;
  const char* to;
  const char* message;
};

TEST_F(GltfModel, MalformedModelsAreRefusedNamingTheElement) {
  const BadModel cases[] = {
      {"indices beyond their buffer view", "\"count\": 36", "\"count\": 37",
       "37 elements from byte 0 go beyond buffer view 2 of 72 bytes"},
      {"an index out of range", "\"count\": 24", "\"count\": 20",
       "meshes[0].primitives[0].indices: index 20 out of range 0..19"},
      {"a node that is its own ancestor", "\"children\": [\n    2\n   ]",
       "\"children\": [\n    1\n   ]", "nodes[1] ('hangar'): is its own ancestor"},
      {"a buffer outside the model's folder", "\"uri\": \"hangar.bin\"",
       "\"uri\": \"../../../../etc/hostname\"", "is outside the model's folder"},
      {"a missing buffer file", "\"uri\": \"hangar.bin\"", "\"uri\": \"missing.bin\"",
       "not a valid glTF file"},
      {"a mesh that does not exist", "\"mesh\": 0", "\"mesh\": 7",
       "nodes[2].mesh: mesh 7 does not exist"},
      {"not JSON", "\"asset\"", "asset", "not a valid glTF file"},
  };
  for (const BadModel& c : cases) {
    SCOPED_TRACE(c.what);
    const Result r = Render(Malformed(c.from, c.to), kCamera, "x.exr");
    EXPECT_NE(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find(c.message), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("Segmentation"), std::string::npos);
  }
}

// Node graphs that are not trees, a model over the triangle budget and a structure of the wrong
// JSON type: aperture-render exits with status 2 and the message, within 2 GB of address space
// (the DAG of depth 40 expanded as a tree is 2^40 triangles, the budget model 2 * 10^9).
TEST_F(GltfModel, BadGraphsBudgetsAndStructuresExitWithStatus2) {
  namespace t = aperture::testing;
  const std::string two_parents = t::GltfFile(
      R"([{"children": [1, 2]}, {"children": [3]}, {"children": [3]}, {"name": "wheel", "mesh": 0}])",
      R"([{"nodes": [0]}])");
  const std::string bad_array = t::PrimitivesAsObject();
  const struct {
    const char* file;
    std::string content;
    std::string message;
  } cases[] = {
      {"dag40.gltf", t::DuplicatedChildDag(40),
       "dag40.gltf: nodes[40]: listed twice as a child by nodes[39]; glTF nodes form a tree"},
      {"two_parents.gltf", two_parents,
       "two_parents.gltf: nodes[3] ('wheel'): listed as a child by nodes[1] and nodes[2]; glTF "
       "nodes form a tree"},
      {"cycle.gltf", t::GltfFile(R"([{"mesh": 0}, {"children": [2]}, {"children": [1]}])"),
       "cycle.gltf: nodes[1]: is its own ancestor (nodes[1] -> nodes[2] -> nodes[1], parent to "
       "child: a cycle of 2 nodes)"},
      {"budget.gltf", t::InstancedMesh(20'000, t::ByteStripMesh(100'000)),
       "budget.gltf: the model's nodes place 2000000000 triangles (a mesh counted once for each "
       "node that places it), above the budget of 4000000 triangles per model"},
      {"bad_array.gltf", bad_array, "bad_array.gltf: meshes[0].primitives: expected an array"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.file);
    std::ofstream(Path(c.file)) << c.content;
    const Result r = aperture::testing::RunProcess(
        "ulimit -v 2000000; " + std::string(APERTURE_RENDER_BIN) + " --scene " + Path(c.file) +
        " --size 64x48 --nopreview --store none -o " + Path("x.exr"));
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("aperture-render: error: "), std::string::npos) << r.output;
    EXPECT_NE(r.output.find(c.message), std::string::npos) << r.output;
  }
}

// 100,000 nested nodes render: no walk of the tree uses the call stack, which a recursive one
// would overflow near 20,000 levels.
TEST_F(GltfModel, ADeepChainOfNodesRenders) {
  std::ofstream(Path("chain.gltf")) << aperture::testing::NestedChain(100'000);
  // The triangle at z = -100 (0.001 per level), seen from z = -99.
  const Result r = Render(Path("chain.gltf"), "--camera 0.3,0.3,-99,0,0,0 --fov 60", "chain.exr");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::vector<float> pixels = Pixels("chain.exr");
  ASSERT_EQ(pixels.size(), 320u * 240 * 4);
  // The triangle (white, unlit as the default material is drawn) covers the centre.
  const size_t centre = (120 * 320 + 160) * 4;
  EXPECT_GT(pixels[centre], 0.5f);
}

}  // namespace
