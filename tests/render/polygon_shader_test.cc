// The batched shading paths (a row of a covered leaf, the points of a mixed leaf) give exactly
// the colours of shading one point at a time, for every filter mode and polygon of the demo.
#include "render/polygon_shader.h"

#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "scene/demo_scene.h"
#include "scene/scene_builder.h"
#include "texture/prefiltered_table.h"

namespace aperture {
namespace {

bool Same(const Rgba& a, const Rgba& b) {
  return a.r == b.r && a.g == b.g && a.b == b.b && a.a == b.a;
}

TEST(PolygonShader, BatchedShadingEqualsOnePointAtATime) {
  auto scene = BuildScene(MakeDemoScene());
  ASSERT_TRUE(scene.ok()) << scene.status();
  constexpr int kWidth = 320, kHeight = 180;
  const FrameGeometry geometry = ProjectScene(*scene, DemoCamera(), kWidth, kHeight, 2.0);
  ASSERT_GT(geometry.polygons.size(), 10u);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> x_of(0, kWidth), y_of(0, kHeight);
  for (FilterMode mode : {FilterMode::kNearest, FilterMode::kTrilinear, FilterMode::kAniso}) {
    SCOPED_TRACE(FilterModeName(mode));
    ShadingOptions options;
    options.override_filter = true;
    options.filter = mode;
    const absl::StatusOr<PolygonShader> made = PolygonShader::Create(*scene, geometry, options);
    ASSERT_TRUE(made.ok()) << made.status();
    const PolygonShader& shader = *made;
    int compared = 0;
    for (int index = 0; index < static_cast<int>(geometry.polygons.size()); index += 7) {
      // A row of 150 pixel centres (more than one batch, not a multiple of it).
      const double x0 = 10.5, y = 20.5 + index % 150;
      std::vector<Rgba> row(150);
      shader.ShadeRow(index, x0, y, static_cast<int>(row.size()), row.data());
      for (int i = 0; i < static_cast<int>(row.size()); ++i, ++compared)
        ASSERT_TRUE(Same(row[i], shader.Shade(index, x0 + i, y))) << index << " " << i;
      // Scattered points.
      std::vector<Vec2> points(70);
      for (Vec2& p : points) p = {x_of(rng), y_of(rng)};
      std::vector<Rgba> many(points.size());
      shader.ShadeMany(index, points.data(), static_cast<int>(points.size()), many.data());
      for (size_t i = 0; i < points.size(); ++i, ++compared)
        ASSERT_TRUE(Same(many[i], shader.Shade(index, points[i].x, points[i].y))) << index;
    }
    EXPECT_GT(compared, 1000);
  }
}

// A filter that cannot be built is an error naming the material, the texture and the filter, not
// another filter drawn in its place. The table's size limit makes the aniso filter fail here:
// no texture of a scene file is that large, but a table that cannot be built or read from the
// store fails the same way.
TEST(PolygonShader, AFilterThatCannotBeBuiltIsAnErrorNamingIt) {
  auto scene = BuildScene(MakeDemoScene());
  ASSERT_TRUE(scene.ok()) << scene.status();
  const int too_wide = (1 << kTableMaxLog2Size) * 2;
  for (auto& texture : scene->textures)
    texture = MakeSceneTexture("too-wide", Image(too_wide, 1, Rgba{0.5f, 0.5f, 0.5f, 1}), nullptr);
  const FrameGeometry geometry = ProjectScene(*scene, DemoCamera(), 64, 36, 2.0);
  ShadingOptions options;
  options.override_filter = true;
  options.filter = FilterMode::kAniso;
  const absl::StatusOr<PolygonShader> made = PolygonShader::Create(*scene, geometry, options);
  ASSERT_FALSE(made.ok());
  EXPECT_EQ(made.status().code(), absl::StatusCode::kInvalidArgument);
  const std::string message(made.status().message());
  EXPECT_NE(message.find("materials ('"), std::string::npos) << message;
  EXPECT_NE(message.find("texture 'too-wide'"), std::string::npos) << message;
  EXPECT_NE(message.find("aniso filter"), std::string::npos) << message;
  // The mip-map's filters need no table: the same scene shades with trilinear.
  options.filter = FilterMode::kTrilinear;
  EXPECT_TRUE(PolygonShader::Create(*scene, geometry, options).ok());
}

}  // namespace
}  // namespace aperture
