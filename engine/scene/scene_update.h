// Per-frame state of a live channel: a SceneUpdate moves, shows or hides named objects
// and changes the sun, ambient, fog, sky and time of day of a built scene in place. A moved
// object's polygons are placed again by the builder's own code (object_placement), so the updated
// scene holds what a fresh build of the moved scene would, polygon for polygon. The cost is in
// proportion to what the update names: each entry finds its object through the scene's name index,
// each moved object is placed again, and when objects are shown or hidden the polygon array is laid
// out again once (never a rebuild of the scene).
#pragma once

#include <functional>
#include <string>

#include "absl/container/flat_hash_map.h"
#include "absl/status/status.h"
#include "aperture/v1/scene.pb.h"
#include "scene/scene.h"

namespace aperture {

// Whether `update` would apply to `scene`: every object name is one of its named objects and
// every value is valid. The error names the first offending field ("update.objects[2] ('jet'):
// ..."). `stop` is asked every few thousand entries; when it says stop the answer is CANCELLED,
// naming how far the check got.
absl::Status CheckSceneUpdate(const Scene& scene, const v1::SceneUpdate& update,
                              const std::function<bool()>& stop = nullptr);

// Applies `update` to `scene`, all or nothing: on error (also when `stop` says stop, CANCELLED)
// the scene is unchanged.
absl::Status ApplySceneUpdate(const v1::SceneUpdate& update, Scene* scene,
                              const std::function<bool()>& stop = nullptr);

// The updates of frames that were skipped, merged in order into the one update that applying
// them in turn makes: one entry per object (the later transform or visibility where it sets one),
// each scene value from the later one where it sets it. Merging costs in proportion to the later
// update, whatever has been merged before.
class MergedSceneUpdate {
 public:
  void Merge(const v1::SceneUpdate& later);
  bool empty() const { return empty_; }
  // The merged update; this becomes empty.
  v1::SceneUpdate Take();

 private:
  v1::SceneUpdate merged_;
  absl::flat_hash_map<std::string, int> entry_;              // object name -> its entry in merged_
  absl::flat_hash_map<std::string, int> light_group_entry_;  // group -> its entry in merged_
  bool empty_ = true;
};

// `earlier` becomes the update that applying `earlier` and then `later` makes (MergedSceneUpdate
// of the two).
void MergeSceneUpdate(const v1::SceneUpdate& later, v1::SceneUpdate* earlier);

}  // namespace aperture
