// Geometry and materials the built-in airfields share (scene/demo_scene, scene/airport_scene):
// boxes, tanks and a twin-jet as proto meshes, materials and embedded textures.
#pragma once

#include <initializer_list>

#include "aperture/v1/scene.pb.h"
#include "base/image.h"
#include "scene/vec.h"

namespace aperture::demo {

void SetColor(v1::Color* c, float r, float g, float b);
v1::Polygon* AddPolygon(v1::Mesh* mesh, std::initializer_list<Vec3> vertices);
// A horizontal rectangle at height y, counter-clockwise seen from above.
void AddFlatRect(v1::Mesh* mesh, double x0, double z0, double x1, double z1, double y);
// A closed box on the ground without its bottom face.
void AddBox(v1::Mesh* mesh, double x0, double z0, double x1, double z1, double height);
// A vertical cylinder of `sides` facets with a flat top.
void AddTank(v1::Mesh* mesh, double cx, double cz, double radius, double height, int sides);

// The faces of an axis-aligned box, to leave some out.
enum BoxFace : unsigned {
  kPlusZ = 1,
  kMinusZ = 2,
  kPlusX = 4,
  kMinusX = 8,
  kTop = 16,
  kBottom = 32
};
// An axis-aligned box [lo, hi], every face seen from outside counter-clockwise, except the faces
// in `skip` (one that lies on another box's face would make coplanar overlapping polygons).
void AddSolidBox(v1::Mesh* mesh, const Vec3& lo, const Vec3& hi, unsigned skip = 0);
// A twin-jet the size of an A320 (38 m long, 34 m span) in its own frame: the nose towards -z
// (where yaw 0 looks), the wheels on y = 0, the centre of the fuselage at x = z = 0.
void AddAircraft(v1::Mesh* mesh);
// The demo's sky, ambient light, afternoon sun and light haze (fog), shared by the airport.
void SetDemoWeather(v1::Scene& scene);
// The aircraft mesh (material "livery"), then one object per mesh of the scene: the aircraft is
// the one that moves (named kDemoAircraft, a live channel's updates name it, placed at
// DemoAircraftAt(0)); every other mesh stands once where it was built.
void AddAircraftAndObjects(v1::Scene& scene);

// A lit material of colour (r, g, b), textured by `texture` (one repeat per `repeat` world units,
// seed 000's anisotropic filter) when given.
v1::Material* AddMaterial(v1::Scene& scene, const char* id, float r, float g, float b,
                          const char* texture = nullptr, double repeat = 1);
// `image` as an embedded PNG texture.
void AddEncodedTexture(v1::Scene& scene, const char* id, const Image& image);

}  // namespace aperture::demo
