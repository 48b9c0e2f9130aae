// Spheres and cylinders in scene files: their frames, their texture transform as seed 003's F2,
// and validation errors that name the offending field.
#include <gtest/gtest.h>

#include "scene/scene_builder.h"
#include "scene/scene_file.h"

namespace aperture {
namespace {

absl::StatusOr<Scene> Load(const std::string& curved_json) {
  auto proto = ParseSceneJson(R"({"materials": [{"id": "m", "texture_transform":
      {"repeat_u": 0.25, "repeat_v": 0.5, "offset_u": 0.1}}], )" +
                              curved_json + "}");
  if (!proto.ok()) return proto.status();
  return BuildScene(*proto);
}

Vec3 Column(const Mat3& m, int j) { return {m.m[0][j], m.m[1][j], m.m[2][j]}; }

TEST(CurvedScene, SpheresAndCylindersBuild) {
  auto scene = Load(R"("spheres": [{"center": {"x": 1, "y": 2, "z": 3}, "radius": 0.5,
                                    "material_id": "m"}],
                       "cylinders": [{"base": {"x": 0, "y": 0, "z": -5},
                                      "top": {"x": 3, "y": 0, "z": -5}, "radius": 2,
                                      "capped": true}])");
  ASSERT_TRUE(scene.ok()) << scene.status();
  ASSERT_EQ(scene->curved.size(), 2u);
  const CurvedPrimitive& s = scene->curved[0];
  EXPECT_EQ(s.kind, CurvedKind::kSphere);
  EXPECT_EQ(s.origin, (Vec3{1, 2, 3}));
  EXPECT_EQ(s.radius, 0.5);
  EXPECT_EQ(s.material, 1);
  // The default pole +y gives the world axes as the frame.
  EXPECT_EQ(Column(s.axes, 0), (Vec3{1, 0, 0}));
  EXPECT_EQ(Column(s.axes, 1), (Vec3{0, 1, 0}));
  EXPECT_EQ(Column(s.axes, 2), (Vec3{0, 0, 1}));
  // F2: u = x' / 0.25 + 0.1, v = z' / 0.5.
  EXPECT_DOUBLE_EQ(s.texture.a, 4);
  EXPECT_DOUBLE_EQ(s.texture.d, 2);
  EXPECT_DOUBLE_EQ(s.texture.e, 0.1);
  EXPECT_NEAR(s.texture.b, 0, 1e-15);
  const CurvedPrimitive& c = scene->curved[1];
  EXPECT_EQ(c.kind, CurvedKind::kCylinder);
  EXPECT_DOUBLE_EQ(c.height, 3);
  EXPECT_TRUE(c.capped);
  EXPECT_EQ(c.material, 0);  // none given: the grey default
  const Vec3 axis = Column(c.axes, 1);
  EXPECT_NEAR(axis.x, 1, 1e-15);
  EXPECT_NEAR(Dot(Column(c.axes, 0), axis), 0, 1e-15);
  EXPECT_NEAR(Dot(Column(c.axes, 2), axis), 0, 1e-15);
  EXPECT_NEAR(Dot(Cross(Column(c.axes, 0), axis), Column(c.axes, 2)), 1, 1e-15);  // right-handed
}

TEST(CurvedScene, ValidationNamesTheField) {
  const struct {
    const char* json;
    const char* message;
  } cases[] = {
      {R"("spheres": [{"radius": "NaN"}])", "spheres[0].radius: is NaN or infinite"},
      {R"("spheres": [{"radius": 1}, {"radius": -2}])", "spheres[1].radius: must be > 0, is -2"},
      {R"("spheres": [{}])", "spheres[0].radius: must be > 0, is 0"},
      {R"("spheres": [{"radius": 1, "center": {"y": "Infinity"}}])",
       "spheres[0].center: coordinate is NaN or infinite"},
      {R"("spheres": [{"radius": 1, "pole": {"x": 0}}])",
       "spheres[0].pole: must be a finite non-zero direction"},
      {R"("spheres": [{"radius": 1, "material_id": "nope"}])",
       "spheres[0]: material_id 'nope' is not a material of the scene"},
      {R"("cylinders": [{"radius": 1}])",
       "cylinders[0].top: must differ from base (the cylinder has no length)"},
      {R"("cylinders": [{"radius": "-Infinity", "top": {"y": 1}}])",
       "cylinders[0].radius: is NaN or infinite"},
      {R"("cylinders": [{"radius": 0.5, "top": {"y": 1}, "base": {"x": "NaN"}}])",
       "cylinders[0].base: coordinate is NaN or infinite"},
      {R"("cylinders": [{"radius": 0.5, "top": {"y": 1}, "height": 3}])", "height"},
  };
  for (const auto& c : cases) {
    auto scene = Load(c.json);
    ASSERT_FALSE(scene.ok()) << c.json;
    EXPECT_NE(std::string(scene.status().message()).find(c.message), std::string::npos)
        << scene.status();
  }
}

}  // namespace
}  // namespace aperture
