// The engine's pixel types, used by every stage: a linear-float RGBA colour and image (the
// in-memory form of every raster texture before prefiltering, and of every rendered frame).
// Reading and writing image files is elsewhere (texture/image_file.h, io/exr_writer.h).
#pragma once

#include <cstddef>
#include <memory>
#include <span>
#include <utility>
#include <vector>

namespace aperture {

struct Rgba {
  float r = 0, g = 0, b = 0, a = 0;

  Rgba operator+(const Rgba& o) const { return {r + o.r, g + o.g, b + o.b, a + o.a}; }
  Rgba operator*(float s) const { return {r * s, g * s, b * s, a * s}; }
  Rgba operator*(const Rgba& o) const { return {r * o.r, g * o.g, b * o.b, a * o.a}; }
  bool operator==(const Rgba&) const = default;
};

// Leaves elements unconstructed when no value is given, so that a frame buffer is first touched
// (and its pages faulted in) by the parallel workers that write it, not serially up front.
template <typename T>
struct UninitializedAllocator : std::allocator<T> {
  template <typename U>
  struct rebind {
    using other = UninitializedAllocator<U>;
  };
  template <typename U>
  void construct(U*) noexcept {}
  template <typename U, typename... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};

class Image {
 public:
  Image() = default;
  Image(int width, int height, Rgba fill = {});
  // Every texel must be written before it is read.
  static Image Uninitialized(int width, int height);

  int width() const { return width_; }
  int height() const { return height_; }
  bool empty() const { return width_ == 0 || height_ == 0; }

  Rgba& at(int x, int y) { return texels_[static_cast<size_t>(y) * width_ + x]; }
  const Rgba& at(int x, int y) const { return texels_[static_cast<size_t>(y) * width_ + x]; }
  std::span<const Rgba> texels() const { return texels_; }
  std::span<Rgba> texels() { return texels_; }

 private:
  int width_ = 0;
  int height_ = 0;
  std::vector<Rgba, UninitializedAllocator<Rgba>> texels_;
};

// `cells` x `cells` squares on a `size` x `size` image; the top-left square has colour `a`.
Image MakeCheckerboard(int size, int cells, Rgba a, Rgba b);

bool IsPowerOfTwo(int n);

}  // namespace aperture
