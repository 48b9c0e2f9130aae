#include "base/image.h"

#include <algorithm>

namespace aperture {

Image::Image(int width, int height, Rgba fill)
    : width_(width), height_(height), texels_(static_cast<size_t>(width) * height, fill) {}

Image Image::Uninitialized(int width, int height) {
  Image image;
  image.width_ = width;
  image.height_ = height;
  image.texels_.resize(static_cast<size_t>(width) * height);
  return image;
}

Image MakeCheckerboard(int size, int cells, Rgba a, Rgba b) {
  Image image(size, size);
  const int cell = std::max(1, size / std::max(1, cells));
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) image.at(x, y) = ((x / cell + y / cell) % 2 == 0) ? a : b;
  return image;
}

bool IsPowerOfTwo(int n) { return n > 0 && (n & (n - 1)) == 0; }

}  // namespace aperture
