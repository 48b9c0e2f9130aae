// Scenes whose textures are packed vector textures (.apv, seed 001).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "render/frame_renderer.h"
#include "scene/scene_builder.h"
#include "texture/packed/apv_file.h"
#include "texture/packed/palette.h"

namespace aperture {
namespace {

// A 64 x 64 texture of 8 x 8 squares, black and white.
packed::PackedTexture Checker() {
  packed::IndexedImage image;
  image.width = image.height = 64;
  image.palette = {packed::PackRgba8(0, 0, 0, 255), packed::PackRgba8(255, 255, 255, 255)};
  for (uint32_t y = 0; y < 64; ++y)
    for (uint32_t x = 0; x < 64; ++x) image.indices.push_back(((x / 8 + y / 8) % 2) ? 1 : 0);
  auto texture = packed::PackTexture(image, packed::Curve::kHilbert);
  EXPECT_TRUE(texture.ok()) << texture.status();
  return std::move(*texture);
}

class PackedSceneTexture : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() / ("apv_scene_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir_);
    ASSERT_TRUE(packed::WriteApvFile((dir_ / "checker.apv").string(), Checker().view()).ok());
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  absl::StatusOr<Scene> Load(const std::string& file) {
    v1::Scene proto;
    v1::Texture* t = proto.add_textures();
    t->set_id("map");
    t->set_file(file);
    SceneBuildOptions options;
    options.base_dir = dir_.string();
    return BuildScene(proto, options);
  }
  std::filesystem::path dir_;
};

TEST_F(PackedSceneTexture, NearestAndAreaSamplingWithoutUnpacking) {
  auto scene = Load("checker.apv");
  ASSERT_TRUE(scene.ok()) << scene.status();
  const SceneTexture& texture = *scene->textures[0];
  ASSERT_NE(texture.packed, nullptr);
  // Nearest at the centre of texel (12, 3): square (1, 0), white.
  TextureFootprint f{12.5 / 64, 3.5 / 64, 0, 0, 0, 0};
  EXPECT_FLOAT_EQ((*texture.Sampler(FilterMode::kNearest))->Sample(f).r, 1.0f);
  // Any other mode integrates the footprint exactly: one whole period is half white.
  f = {0.25, 0.5, 1.0f, 0, 0, 1.0f};
  EXPECT_NEAR((*texture.Sampler(FilterMode::kTrilinear))->Sample(f).g, 0.5f, 1e-6);
  // A 4 x 1 texel footprint straddling the black/white edge at x = 8: half white.
  f = {8.0 / 64, 3.5 / 64, 4.0f / 64, 0, 0, 1.0f / 64};
  EXPECT_NEAR((*texture.Sampler(FilterMode::kAniso))->Sample(f).b, 0.5f, 1e-6);
}

TEST_F(PackedSceneTexture, BatchedNearestEqualsOneTexelAtATime) {
  auto scene = Load("checker.apv");
  ASSERT_TRUE(scene.ok()) << scene.status();
  const TextureSampler& nearest = **scene->textures[0]->Sampler(FilterMode::kNearest);
  // 1000 points (several batches of 256) over a few periods, negative coordinates included.
  std::vector<TextureFootprint> in;
  for (int i = 0; i < 1000; ++i)
    in.push_back({-1.5 + 0.00731 * i, 2.25 - 0.00517 * i, 0.001f, 0, 0, 0.001f});
  std::vector<Rgba> batch(in.size());
  nearest.SampleMany(in.data(), batch.data(), static_cast<int>(in.size()));
  int white = 0;
  for (size_t i = 0; i < in.size(); ++i) {
    const Rgba one = nearest.Sample(in[i]);
    ASSERT_EQ(batch[i].r, one.r) << i;
    ASSERT_EQ(batch[i].g, one.g) << i;
    ASSERT_EQ(batch[i].b, one.b) << i;
    ASSERT_EQ(batch[i].a, one.a) << i;
    white += one.r == 1.0f;
  }
  EXPECT_GT(white, 300);  // both colours are met
  EXPECT_LT(white, 700);
}

TEST_F(PackedSceneTexture, RendersInAScene) {
  auto proto_scene = [&] {
    v1::Scene proto;
    v1::Texture* t = proto.add_textures();
    t->set_id("map");
    t->set_file("checker.apv");
    v1::Material* m = proto.add_materials();
    m->set_id("ground");
    m->set_texture_id("map");
    m->set_unlit(true);
    m->mutable_texture_transform()->set_repeat_u(64);  // squares of 8 m
    v1::Mesh* mesh = proto.add_meshes();
    mesh->set_id("plane");
    mesh->set_material_id("ground");
    v1::Polygon* p = mesh->add_polygons();
    for (auto [x, z] : {std::pair{-50.0, 50.0}, {50.0, 50.0}, {50.0, -50.0}, {-50.0, -50.0}}) {
      v1::Vec3* v = p->add_vertices();
      v->set_x(x);
      v->set_z(z);
    }
    return proto;
  }();
  SceneBuildOptions options;
  options.base_dir = dir_.string();
  auto scene = BuildScene(proto_scene, options);
  ASSERT_TRUE(scene.ok()) << scene.status();
  RenderSettings settings;
  settings.width = 64;
  settings.height = 48;
  Camera camera;
  camera.position = {0.3, 2, 0.1};
  camera.pitch_deg = -30;
  auto frame = RenderFrame(*scene, camera, settings);
  ASSERT_TRUE(frame.ok()) << frame.status();
  // Near the bottom the squares are large: black and white pixels both appear.
  float lo = 1, hi = 0;
  for (int x = 0; x < 64; ++x) {
    lo = std::min(lo, frame->image.at(x, 46).r);
    hi = std::max(hi, frame->image.at(x, 46).r);
  }
  EXPECT_LT(lo, 0.1f);
  EXPECT_GT(hi, 0.9f);
}

TEST_F(PackedSceneTexture, CorruptFileIsAnErrorNamingTheTexture) {
  {
    std::fstream file(dir_ / "checker.apv", std::ios::in | std::ios::out | std::ios::binary);
    file.seekp(40);
    file.put('\x7f');
  }
  auto scene = Load("checker.apv");
  ASSERT_FALSE(scene.ok());
  EXPECT_NE(scene.status().message().find("textures[0] ('map')"), std::string::npos)
      << scene.status().message();
  auto missing = Load("nowhere.apv");
  ASSERT_FALSE(missing.ok());
  EXPECT_NE(missing.status().message().find("nowhere.apv"), std::string::npos);
}

}  // namespace
}  // namespace aperture
