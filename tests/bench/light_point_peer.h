// Light points the way OpenSceneGraph-based image generators draw them (osgSim's LightPointNode
// and LightPointDrawable), through Mesa llvmpipe (OSMesa), for the light benchmark
// (light_blink_bench.cc): GL_POINTS with GL_POINT_SMOOTH (nicest), additive blending
// (GL_SRC_ALPHA, GL_ONE), depth tested but not written, each light's point size from its
// projected lamp radius times the square root of its intensity, clamped to a minimum size,
// sub-pixel points faded by alpha, fractional sizes drawn as two points of the neighbouring
// integer sizes. Measured frames go to buffers that hide nothing of what the rasterizer does: 1x
// to a 16-bit fixed-point colour buffer, which like the 8-bit buffer of an image generator clamps
// each fragment to [0, 1] (llvmpipe's smooth points rely on it: their coverage alpha exceeds 1
// inside the point), with steps of 1/65535 instead of 1/255; 4x MSAA to a float buffer resolved
// into another (multisampled, llvmpipe ignores GL_POINT_SMOOTH and draws squares, so nothing
// needs the clamp, and float keeps dim points from rounding).
#pragma once

#include <GL/osmesa.h>

#include <cstdint>
#include <string>
#include <vector>

#include "base/pixel_rect.h"
#include "scene/camera.h"
#include "scene/vec.h"

namespace aperture {

// One GL point: an integer size (diameter, pixels) and the alpha it is blended with.
struct SizedPoint {
  int size = 1;
  double alpha = 1;
};

// osgSim's sizing of a light point, additive mode: `pixel_size` (its projected radius in pixels
// times the square root of its intensity) raised to `min_size`; below one pixel a size-1 point
// faded by alpha; between sizes n and n + 1 the two points, weighted by (1 - f^2) and f^2 for the
// fraction f, the alpha dimmed by 2/3 + sqrt(raw / clamped) / 3 where the minimum raised it; at
// `max_size` and past it one point of that size.
std::vector<SizedPoint> OsgSimPointSizes(double pixel_size, double min_size, double max_size = 30);

// What the sized points would add up to if a point of size s covered exactly the disc of
// diameter s: sum of alpha x pi s^2 / 4, in pixels.
double NominalArea(const std::vector<SizedPoint>& points);

// A point to draw: position relative to the camera (GL floats stay precise near the eye),
// linear colour (at most 1: the buffers clamp) and its size and alpha.
struct PeerPoint {
  Vec3 offset;
  float r = 0, g = 0, b = 0;
  SizedPoint point;
};

// Draws `points` into the bound framebuffer with LightPointDrawable's state for additive light
// points (above), from vertex arrays, one glDrawArrays per point size, as osgSim does; the
// modelview must hold the camera's orientation alone (the offsets are from its position).
// Turns texturing and the alpha test off; leaves blending and point smoothing on, depth writes on.
void DrawOsgSimPoints(const std::vector<PeerPoint>& points);

class LightPointPeer {
 public:
  ~LightPointPeer();
  // The OSMesa context; false (and a message on stderr) when it cannot be made or its buffers do
  // not read back what was drawn.
  bool Init();
  std::string Renderer() const;
  // The buffers of this size (above), 1x and 4x MSAA, each drawn buffer with a 24-bit depth
  // buffer.
  bool Resize(int width, int height);

  // The camera's projection and orientation (its position is subtracted from every vertex).
  void SetCamera(const Camera& camera, double near = 0.5, double far = 20000);
  // Binds the 1x or 4x buffer and clears `window` (all of the frame when it is empty).
  void Begin(bool msaa, const PixelRect& window = {});
  // An opaque quad (depth written), world vertices counter-clockwise or not.
  void DrawQuad(const Vec3 corners[4], float grey);
  // The points with osgSim's state, grouped by size (DrawOsgSimPoints).
  void DrawPoints(const std::vector<PeerPoint>& points) { DrawOsgSimPoints(points); }
  // Resolves the 4x buffer over `window` (all of the frame when empty) and waits for llvmpipe to
  // finish.
  void End(const PixelRect& window = {});
  // The Rec. 709 luminance of each pixel of `window` in the last frame, row by row from the top.
  std::vector<double> WindowLuminance(const PixelRect& window);

 private:
  // GL's window rectangle (origin bottom left) of a frame rectangle (origin top left).
  PixelRect GlRect(const PixelRect& window) const;

  // A framebuffer object and its renderbuffers.
  struct Target {
    unsigned fbo = 0, color = 0, depth = 0;
  };
  bool Make(Target& target, unsigned format, int samples, bool depth);
  void Free(Target& target);

  OSMesaContext context_ = nullptr;
  std::vector<uint32_t> dummy_;  // the context's own buffer, unused: frames go to the targets
  int width_ = 0, height_ = 0;
  // 1x 16-bit, 4x float and its float resolve.
  Target single_, multi_, resolved_;
  const Target* drawn_ = nullptr;
  const Target* resolve_to_ = nullptr;  // null: the drawn target is read
  const Target* read_ = nullptr;
  Vec3 eye_;
  std::vector<float> readback_;
};

}  // namespace aperture
