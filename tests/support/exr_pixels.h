// An image file's pixels as OpenImageIO reads them: every channel as float, row by row.
#pragma once

#include <OpenImageIO/imagebuf.h>

#include <string>
#include <vector>

namespace aperture::testing {

// The pixels of `path` with its size in `width` and `height`; empty when it cannot be read.
inline std::vector<float> ReadPixels(const std::string& path, int* width, int* height) {
  OIIO::ImageBuf image(path);
  if (!image.read(0, 0, true, OIIO::TypeDesc::FLOAT)) return {};
  const OIIO::ImageSpec& spec = image.spec();
  *width = spec.width;
  *height = spec.height;
  std::vector<float> pixels(static_cast<size_t>(spec.width) * spec.height * spec.nchannels);
  image.get_pixels(OIIO::ROI::All(), OIIO::TypeDesc::FLOAT, pixels.data());
  return pixels;
}

}  // namespace aperture::testing
