// Every light point of a scene as the GL points an osgSim-based image generator draws for one
// frame (light_point_peer.h; night_load_bench.cc's llvmpipe frame): what its cull traversal does
// each frame, per light: the light's place (on its object, when it has one), its intensity
// towards the eye (lobe, group, flashing at the frame's scene time), and its point sizes
// (light_measure.h's PeerLightOf). Lights behind the near plane or off the frame by more than the
// largest point's radius are culled first, as a cull traversal does; lights dark towards the eye
// are left out too.
#pragma once

#include <vector>

#include "light_point_peer.h"
#include "scene/camera.h"
#include "scene/scene.h"

namespace aperture {

struct ScenePeerPoints {
  std::vector<PeerPoint> points;
  size_t lights = 0;  // the lights they draw
};

// The points of `scene`'s lights in the `width` x `height` frame of `camera` at scene time
// `time_s`, at least `min_size` pixels across (osgSim's minimum point size), into `out` (its
// arrays reused from frame to frame, as an image generator's are).
void ScenePeerPointsOf(const Scene& scene, const Camera& camera, int width, int height,
                       double time_s, double min_size, ScenePeerPoints& out);

}  // namespace aperture
