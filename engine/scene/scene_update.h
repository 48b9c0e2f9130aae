// Per-frame state of a live channel (issue 20): a SceneUpdate moves, shows or hides named objects
// and changes the sun, ambient, fog and sky of a built scene in place. A moved object's polygons
// are placed again by the builder's own code (object_placement), so the updated scene holds what
// a fresh build of the moved scene would, polygon for polygon; the cost is that of the objects
// that moved (plus shifting the polygon array when an object is shown or hidden), never a rebuild.
#pragma once

#include "absl/status/status.h"
#include "aperture/v1/scene.pb.h"
#include "scene/scene.h"

namespace aperture {

// Whether `update` would apply to `scene`: every object name is one of its named objects and
// every value is valid. The error names the first offending field ("update.objects[2] ('jet'):
// ...").
absl::Status CheckSceneUpdate(const Scene& scene, const v1::SceneUpdate& update);

// Applies `update` to `scene`, all or nothing: on error the scene is unchanged.
absl::Status ApplySceneUpdate(const v1::SceneUpdate& update, Scene* scene);

// `earlier` becomes the update that applying `earlier` and then `later` makes: one entry per
// object (the later transform or visibility where it sets one), each scene value from the later
// one where it sets it.
void MergeSceneUpdate(const v1::SceneUpdate& later, v1::SceneUpdate* earlier);

}  // namespace aperture
