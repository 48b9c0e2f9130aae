// The header every producer of frames writes (aperture-render, the server, each region of a split
// frame): scene, camera, render mode and times, software name and version, and the frame's place
// (a region's data window inside the whole frame's display window, so that it opens at its place
// in the frame).
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "render/renderer.h"
#include "scene/camera.h"

namespace aperture {

struct ExrMetadata {
  std::string scene_name;
  std::string camera;  // "X,Y,Z,YAW,PITCH,ROLL fov=..."
  std::string mode;    // "raster" or "raytrace"
  double setup_ms = 0, raster_ms = 0;
  // Where the image lies in its frame: the data window's top-left corner and the display window's
  // size. frame_width 0: the image is the whole frame.
  int x = 0, y = 0, frame_width = 0, frame_height = 0;
  std::vector<std::pair<std::string, std::string>> extra;  // more string attributes
};

// One attribute of the header: text, or a number written as a float.
struct ExrAttribute {
  std::string name;
  std::string text;
  float number = 0;
  bool is_number = false;
};

// The attributes both encoders write, in order (the windows are set apart, as required ones).
std::vector<ExrAttribute> HeaderAttributes(const ExrMetadata& m);

// "X,Y,Z,YAW,PITCH,ROLL fov=F" (off-axis frusta add their four angles).
std::string CameraText(const Camera& camera);

// The header of a rendered frame (or region) of a frame_width x frame_height frame.
ExrMetadata FrameMetadata(const std::string& scene_name, const Camera& camera,
                          const RenderedFrame& frame, int frame_width, int frame_height,
                          const char* mode);

}  // namespace aperture
