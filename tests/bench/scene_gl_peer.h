// An engine scene drawn through Mesa llvmpipe (OSMesa) the way a fixed-function GL image generator
// draws it, for the night scene's load benchmark (night_load_bench.cc): the scene's convex
// polygons as triangle fans in one vertex buffer (positions relative to the camera, texture
// coordinates from each polygon's planar mapping, and as vertex colour the material's colour times
// the polygon's constant light, scene/shading.h's SurfaceLight, for the side the camera sees),
// drawn in batches by material state: opaque first, then alpha-tested cut-outs (MASK), then
// blended (BLEND) without depth writes; single-sided materials back-face culled. Textures are
// RGBA8 with glGenerateMipmap's pyramid, GL_LINEAR_MIPMAP_LINEAR (trilinear), repeated
// (gl_texels.h: a packed vector texture decoded to a raster; a texture of neither kind drawn as its
// mean colour, which TextureNotes() says). The scene's fog is GL's exponential fog by eye depth;
// the sky is the clear colour. Then the light points (light_point_peer.h's DrawOsgSimPoints), into
// an 8-bit frame, 1x or 4x MSAA (resolved by a blit), as an image generator's display buffer is.
// The vertex colours and depths are computed once for the scene's camera (the benchmark's camera
// does not move), so a frame's vertex work is GL's transform, clipping and culling. What the
// frames look like only needs to be close to Aperture's: the load is what is compared.
#pragma once

#include <GL/osmesa.h>

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "base/image.h"
#include "light_point_peer.h"
#include "scene/camera.h"
#include "scene/scene.h"

namespace aperture {

// OpenSceneGraph's default near plane: its cull traversal sets the far plane at the farthest
// visible bound and keeps the near plane at least this share of it (CullSettings' nearFarRatio),
// which spares a 24-bit depth buffer the z-fighting of a near plane at 1 m over kilometres of
// layered ground (the motorway lies 15 mm over the map).
inline constexpr double kOsgNearFarRatio = 0.0005;

struct SceneGlPeerOptions {
  int texture_side = 8192;  // the largest side of a texture given to GL
  // The depth buffer's near plane, metres; 0: as OpenSceneGraph sets it, the larger of the
  // camera's and kOsgNearFarRatio of the far plane, the farthest vertex ahead of the camera.
  double near = 0;
};

class SceneGlPeer {
 public:
  explicit SceneGlPeer(const SceneGlPeerOptions& options = {}) : options_(options) {}
  ~SceneGlPeer();
  SceneGlPeer(const SceneGlPeer&) = delete;
  SceneGlPeer& operator=(const SceneGlPeer&) = delete;

  // The OSMesa context; false (and a message on stderr) when it cannot be made.
  bool Init();
  std::string Renderer() const;
  // 8-bit colour and 24-bit depth buffers of this size, 1x and 4x MSAA, and the 4x's resolve.
  bool Resize(int width, int height);

  // Uploads the polygons of `scene` as `camera` sees them (the vertex colours and the vertices'
  // origin are the camera's), and the textures it names that no earlier scene uploaded (by id).
  // Returns the scene's handle for Draw.
  absl::StatusOr<int> AddScene(const Scene& scene, const Camera& camera);
  // The near and far planes scene `scene` is drawn with.
  double Near(int scene) const { return scenes_[scene].near; }
  double Far(int scene) const { return scenes_[scene].far; }
  size_t Triangles(int scene) const { return scenes_[scene].triangles; }
  // How each texture was given to GL, one line each.
  const std::vector<std::string>& TextureNotes() const { return notes_; }

  // Draws scene `scene` and then `points` (none when null) into the 1x or the 4x buffer, resolves
  // the 4x one, and waits for llvmpipe to finish: milliseconds from the clear to glFinish.
  double Draw(int scene, bool msaa, const std::vector<PeerPoint>* points);
  // The last frame drawn, row 0 at the top, 8-bit values as linear floats.
  Image Read() const;

 private:
  struct Target {
    unsigned fbo = 0, color = 0, depth = 0;
  };
  bool Make(Target& target, int samples, bool depth);
  void Free(Target& target);
  // The GL texture of scene texture `index` (0 when it is drawn as its mean colour, `mean`).
  unsigned TextureOf(const Scene& scene, int index, Rgba* mean);

  // Triangles drawn with one material state.
  struct Batch {
    unsigned texture = 0;  // 0: untextured
    AlphaMode alpha = AlphaMode::kOpaque;
    float cutoff = 0.5f;
    bool cull_back = false;
    int first = 0, count = 0;  // vertices
  };
  struct UploadedScene {
    Camera camera;
    double near = 0, far = 0;  // the depth buffer's planes
    unsigned buffer = 0;
    std::vector<Batch> batches;
    size_t triangles = 0;
    Rgba sky;
    Rgba fog_color;
    double fog_density = 0;
  };

  SceneGlPeerOptions options_;
  OSMesaContext context_ = nullptr;
  std::vector<uint32_t> dummy_;  // the context's own buffer, unused: frames go to the targets
  int width_ = 0, height_ = 0;
  Target single_, multi_, resolved_;
  const Target* last_ = nullptr;  // where the last frame can be read
  std::vector<UploadedScene> scenes_;
  struct UploadedTexture {
    unsigned name = 0;      // 0: drawn as `mean`
    Rgba mean{1, 1, 1, 1};  // the vertex colour's factor
  };
  std::map<std::string, UploadedTexture> textures_;  // by texture id
  std::vector<std::string> notes_;
};

}  // namespace aperture
