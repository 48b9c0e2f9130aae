// The scene memory estimate against what a built scene actually holds.
#include "scene/scene_memory.h"

#include <gtest/gtest.h>

#include "scene/scene_builder.h"
#include "texture/prefiltered_table_builder.h"

namespace aperture {
namespace {

TEST(SceneMemory, TexturesAndTablesAreWhatTheBuiltSceneHolds) {
  v1::Scene proto;
  v1::Texture& checks = *proto.add_textures();
  checks.set_id("checks");
  checks.mutable_checkerboard()->set_size(300);  // resampled to 512 x 512
  v1::Material& ground = *proto.add_materials();
  ground.set_id("ground");
  ground.set_texture_id("checks");
  ground.set_filter(v1::TEXTURE_FILTER_ANISO);
  v1::Material& again = *proto.add_materials();  // the same table, counted once
  again.set_id("again");
  again.set_texture_id("checks");
  again.set_filter(v1::TEXTURE_FILTER_ANISO);
  v1::Mesh& mesh = *proto.add_meshes();
  mesh.set_id("m");
  for (int p = 0; p < 10; ++p) {
    v1::Polygon& polygon = *mesh.add_polygons();
    for (int k = 0; k < 3; ++k) {
      v1::Vec3& v = *polygon.add_vertices();
      v.set_x(p + (k == 1));
      v.set_z(k == 2);
    }
  }

  auto estimate = EstimateSceneMemory(proto);
  ASSERT_TRUE(estimate.ok()) << estimate.status();
  auto scene = BuildScene(proto);
  ASSERT_TRUE(scene.ok()) << scene.status();
  const MipPyramid& pyramid = *scene->textures[0]->pyramid;
  uint64_t pyramid_bytes = 0;
  for (int l = 0; l < pyramid.levels(); ++l)
    pyramid_bytes += pyramid.level(l).texels().size_bytes();
  EXPECT_NEAR(static_cast<double>(estimate->texture_bytes), static_cast<double>(pyramid_bytes),
              0.01 * pyramid_bytes);
  auto table = BuildPrefilteredTable(pyramid.level(0));
  ASSERT_TRUE(table.ok());
  EXPECT_NEAR(static_cast<double>(estimate->table_bytes), static_cast<double>(table->bytes.size()),
              0.01 * table->bytes.size());
  EXPECT_GE(estimate->geometry_bytes, scene->polygons.size() * sizeof(ScenePolygon));
  EXPECT_NE(estimate->ToString().find("aniso tables"), std::string::npos);
}

TEST(SceneMemory, AnEncodedTextureIsWeighedByItsHeader) {
  v1::Scene proto;
  proto.add_textures()->set_encoded("not an image at all");
  auto estimate = EstimateSceneMemory(proto);
  EXPECT_FALSE(estimate.ok());
  EXPECT_NE(estimate.status().message().find("textures[0]"), std::string::npos);
}

}  // namespace
}  // namespace aperture
