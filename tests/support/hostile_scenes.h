// Scenes whose content is hostile to exact visibility, shared by the hostile-content tests and
// scripts/bench-hostile.sh (through tests/bench/make_hostile_scenes): crowds of coplanar polygons,
// stacks of layers a millimetre apart, one mesh placed thousands of times at one place. Each
// crowd has a twin whose triangles are the same but spread apart in depth (every triangle on a
// plane of its own), the frame a crowd's cost is measured against. All are seen from the origin
// looking along -z (camera 0,0,0,0,0,0), unlit, a few flat colours.
#pragma once

#include "aperture/v1/scene.pb.h"

namespace aperture::testing {

// 8,000 triangles 1 cm across in the plane z = -0.15 m, 27 deep (decals over decals); `spread`:
// each 0.01 mm behind the one before.
v1::Scene CoplanarCrowdScene(bool spread);

// 8,000 triangles in the plane z = -0.15 m: 296 triangles 1 cm across, each placed 27 times at one
// place (layers of decals, each a copy of the one under it).
v1::Scene CoplanarLayersScene();

// 10 overlapping triangles 17 cm across, placed 20 times 1 mm apart in depth about z = -1 m;
// `spread`: each of the 200 triangles 1 mm behind the one before.
v1::Scene StackedLayersScene(bool spread);

// `copies` named objects of one 1 x 0.8 m quad, all at one place 2 m in front of the camera (what
// an update moving every object to one spot leaves).
v1::Scene CopiesScene(int copies);

}  // namespace aperture::testing
